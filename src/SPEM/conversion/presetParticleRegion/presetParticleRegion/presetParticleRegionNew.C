#include "presetParticleRegion.H"

Foam::autoPtr<Foam::presetParticleRegion> Foam::presetParticleRegion::New
(
    const word& name,
    const dictionary& dict,
    const triMesh& mesh,
    const bodySurfaces& bodies
)
{
    const word regionType(dict.get<word>("type"));

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "The preset particle region selection table is empty: libSPEM"
            << " was not loaded (linked with --as-needed?)"
            << exit(FatalError);
    }

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(regionType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            dict,
            "type",
            regionType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    return cstrIter()(name, dict, mesh, bodies);
}
