#include "rigidBody.H"
#include "checkKeywords.H"

const Foam::Enum<Foam::rigidBody::elementContact>
Foam::rigidBody::elementContactNames
({
    {elementContact::slide, "slide"},
    {elementContact::convert, "convert"}
});


Foam::rigidBody::rigidBody(const word& name, const dictionary& dict)
:
    name_(name),
    shape_(rigidBodyShape::New(dict)),
    motion_(rigidBodyMotion::New(dict, *shape_)),
    elementContact_
    (
        getCheckedEnum
        (
            dict, "fluidElements", elementContactNames, elementContact::slide,
            "of body " + name
        )
    ),
    wallRestitution_(dict.getOrDefault<scalar>("wallRestitution", 0))
{
    // Written to reject NaN as well
    if (!(wallRestitution_ >= 0 && wallRestitution_ <= 1))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'wallRestitution " << wallRestitution_ << "' of "
            << dict.name() << " must lie in [0, 1] (0: no bounce)"
            << exit(FatalIOError);
    }
    // One flat dictionary holds the keywords of both models
    wordList allowed({"shape", "motion", "fluidElements", "wallRestitution"});
    allowed.append(shape_->keywords());
    allowed.append(motion_->keywords());
    checkKeywords(dict, allowed);
}


Foam::boundBox Foam::rigidBody::boundingBox() const
{
    return shape_->bounds(motion_->placement());
}


void Foam::rigidBody::toCurrent
(
    const std::vector<scalar>& X,
    std::vector<scalar>& x
) const
{
    const rigidTransform2D& placement = motion_->placement();
    x.resize(X.size());
    const label n = label(X.size()/2);
    for (label i = 0; i < n; ++i)
    {
        const vector2D p = placement.toCurrent(vector2D(X[2*i], X[2*i + 1]));
        x[2*i] = p.x();
        x[2*i + 1] = p.y();
    }
}


Foam::bodyWallParticles Foam::rigidBody::wallParticles
(
    const scalar spacing,
    const label nLayers
) const
{
    return shape_->wallParticles(spacing, nLayers);
}


std::vector<Foam::scalar> Foam::rigidBody::surfacePoints
(
    const scalar spacing
) const
{
    std::vector<scalar> points;
    toCurrent(shape_->surfacePoints(spacing), points);
    return points;
}


void Foam::rigidBody::advance
(
    const scalar time,
    const scalar deltaT,
    const scalar Fx,
    const scalar Fy,
    const scalar Mz,
    const scalar gx,
    const scalar gy
)
{
    motion_->advance(time, deltaT, Fx, Fy, Mz, gx, gy);
}


void Foam::rigidBody::writeState(dictionary& dict) const
{
    motion_->writeState(dict);
}


void Foam::rigidBody::readState(const dictionary& dict)
{
    motion_->readState(dict);
}
