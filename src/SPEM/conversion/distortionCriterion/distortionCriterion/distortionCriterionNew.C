#include "distortionCriterion.H"

Foam::autoPtr<Foam::distortionCriterion> Foam::distortionCriterion::New
(
    const dictionary& conversionDict
)
{
    const word criterionType
    (
        conversionDict.getOrDefault<word>("criterion", defaultCriterion)
    );

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "The distortion criterion selection table is empty: libSPEM"
            << " was not loaded (linked with --as-needed?)"
            << exit(FatalError);
    }

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(criterionType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            conversionDict,
            "criterion",
            criterionType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    return cstrIter()(conversionDict);
}
