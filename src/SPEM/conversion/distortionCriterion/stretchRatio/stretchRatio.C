#include "stretchRatio.H"
#include "addToRunTimeSelectionTable.H"

#include <cmath>

namespace Foam
{
    defineTypeNameAndDebug(stretchRatio, 0);
    addToRunTimeSelectionTable(distortionCriterion, stretchRatio, dictionary);
}


Foam::scalar Foam::stretchRatio::readLimit(const dictionary& conversionDict)
{
    const scalar limit =
        conversionDict.getOrDefault<scalar>("maxStretchRatio", defaultLimit);

    // Written to reject NaN as well
    if (!(limit > 1))
    {
        FatalIOErrorInFunction(conversionDict)
            << "Entry 'maxStretchRatio " << limit << "' of "
            << conversionDict.name() << " must exceed 1 (1: any deformation"
            << " but a rotation and uniform scaling is distortion)"
            << exit(FatalIOError);
    }
    return limit;
}


Foam::stretchRatio::stretchRatio(const dictionary& conversionDict)
:
    distortionCriterionModel(),
    limit_(readLimit(conversionDict)),
    limitPlusInverse_(limit_ + 1/limit_)
{}


Foam::scalar Foam::stretchRatio::principalStretchRatio
(
    const scalar* x0,
    const scalar* x1,
    const scalar* x2,
    const scalar* X0,
    const scalar* X1,
    const scalar* X2
)
{
    const scalar J00 = x1[0] - x0[0], J01 = x2[0] - x0[0];
    const scalar J10 = x1[1] - x0[1], J11 = x2[1] - x0[1];
    const scalar D00 = X1[0] - X0[0], D01 = X2[0] - X0[0];
    const scalar D10 = X1[1] - X0[1], D11 = X2[1] - X0[1];

    // G = J adj(D) = det(D) F has the stretch ratio of F
    const scalar G00 = J00*D11 - J01*D10;
    const scalar G01 = J01*D00 - J00*D01;
    const scalar G10 = J10*D11 - J11*D10;
    const scalar G11 = J11*D00 - J10*D01;

    // sigma_max,min = (p +- q)/2 with p^2 = |G|^2 + 2 det G and
    // q^2 = |G|^2 - 2 det G written as sums of squares: no cancellation
    // near a ratio of 1, where sqrt(|G|^2 - 2 det G) would be sqrt(rounding)
    const scalar p = std::hypot(G00 + G11, G01 - G10);
    const scalar q = std::hypot(G00 - G11, G01 + G10);
    const scalar twiceSigmaMin = std::abs(p - q);
    if (!(twiceSigmaMin > 0))
    {
        return VGREAT;
    }
    return (p + q)/twiceSigmaMin;
}


void Foam::stretchRatio::describe(Ostream& os) const
{
    os  << "stretchRatio > " << limit_
        << " (principal stretches since t = 0)";
}
