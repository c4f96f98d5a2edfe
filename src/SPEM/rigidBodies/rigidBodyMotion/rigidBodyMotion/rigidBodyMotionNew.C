#include "rigidBodyMotion.H"

Foam::autoPtr<Foam::rigidBodyMotion> Foam::rigidBodyMotion::New
(
    const dictionary& dict,
    const rigidBodyShape& shape
)
{
    const word motionType(dict.get<word>("motion"));

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "The rigid body motion selection table is empty: libSPEM"
            << " was not loaded (linked with --as-needed?)"
            << exit(FatalError);
    }

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(motionType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            dict,
            "motion",
            motionType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    return cstrIter()(dict, shape);
}
