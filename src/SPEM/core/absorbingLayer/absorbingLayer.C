#include "absorbingLayer.H"
#include "checkKeywords.H"
#include "saneRanges.H"
#include "vector.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::absorbingLayer Foam::absorbingLayer::read(const dictionary& dampingDict)
{
    absorbingLayer layer;
    const dictionary* dictPtr = dampingDict.findDict("absorbingLayer");
    if (!dictPtr) return layer;
    const dictionary& dict = *dictPtr;
    checkKeywords(dict, {"min", "max", "thickness", "coefficient"});

    const vector lo = getCheckedVector(dict, "min", saneRange::length);
    const vector hi = getCheckedVector(dict, "max", saneRange::length);
    if (!(hi.x() > lo.x() && hi.y() > lo.y()))
    {
        FatalIOErrorInFunction(dict)
            << "absorbingLayer: max " << hi << " must exceed min " << lo
            << " in x and y (the box without damping)" << exit(FatalIOError);
    }
    layer.box_[0] = lo.x();
    layer.box_[1] = lo.y();
    layer.box_[2] = hi.x();
    layer.box_[3] = hi.y();
    layer.thickness_ = getChecked
    (
        dict, "thickness",
        valueRange{0, 1e4, "m", "positive and below 10 km", true}
    );
    layer.coefficient_ = getChecked(dict, "coefficient", saneRange::damping);
    return layer;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::absorbingLayer::describe(Ostream& os) const
{
    os  << "absorbing layer outside the box (" << box_[0] << ' ' << box_[1]
        << ")-(" << box_[2] << ' ' << box_[3] << ") m: mass-proportional"
        << " damping of the water growing to " << coefficient_ << " 1/s over "
        << thickness_ << " m";
}


// ************************************************************************* //
