#include "presetParticleRegion.H"

namespace Foam
{
    defineTypeNameAndDebug(presetParticleRegion, 0);
    defineRunTimeSelectionTable(presetParticleRegion, dictionary);
}


Foam::presetParticleRegion::presetParticleRegion(const word& name)
:
    name_(name)
{}


Foam::scalar Foam::presetParticleRegion::readPositive
(
    const dictionary& dict,
    const word& key
)
{
    const scalar value = dict.get<scalar>(key);

    // Written to reject NaN as well
    if (!(value > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << ' ' << value << "' of " << dict.name()
            << " must be positive" << exit(FatalIOError);
    }
    return value;
}


Foam::PtrList<Foam::presetParticleRegion> Foam::readPresetParticleRegions
(
    const dictionary& conversionDict,
    const triMesh& mesh,
    const bodySurfaces& bodies
)
{
    PtrList<presetParticleRegion> regions;

    const entry* regionsEntry =
        conversionDict.findEntry("presetParticleRegions", keyType::LITERAL);
    if (!regionsEntry)
    {
        return regions;
    }
    if (!regionsEntry->isDict())
    {
        FatalIOErrorInFunction(conversionDict)
            << "Entry 'presetParticleRegions' of " << conversionDict.name()
            << " must be a dictionary of regions, each a sub-dictionary"
            << " with a type:" << nl
            << "    presetParticleRegions { name { type box; ... } }"
            << exit(FatalIOError);
    }

    const dictionary& regionsDict = regionsEntry->dict();
    for (const entry& e : regionsDict)
    {
        if (!e.isDict())
        {
            FatalIOErrorInFunction(regionsDict)
                << "Entry '" << e.keyword() << "' of " << regionsDict.name()
                << " must be a sub-dictionary: "
                << e.keyword() << " { type box; ... }" << exit(FatalIOError);
        }
        regions.append
        (
            presetParticleRegion::New(e.keyword(), e.dict(), mesh, bodies)
        );
    }

    return regions;
}
