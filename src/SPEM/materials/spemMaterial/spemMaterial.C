#include "spemMaterial.H"

namespace Foam
{
    defineTypeNameAndDebug(spemMaterial, 0);
    defineRunTimeSelectionTable(spemMaterial, dictionary);
}


Foam::scalar Foam::spemMaterial::readPositive(const word& key) const
{
    const scalar value = dict_.get<scalar>(key);
    if (!(value > 0))
    {
        FatalIOErrorInFunction(dict_)
            << "Entry '" << key << "' of region " << name_
            << " must be positive, found " << value << exit(FatalIOError);
    }
    return value;
}


Foam::spemMaterial::spemMaterial(const word& name, const dictionary& dict)
:
    name_(name),
    dict_(dict),
    rho_(readPositive("rho"))
{}


void Foam::spemMaterial::density
(
    const label begin,
    const label end,
    const scalar* grad,
    const scalar* area,
    const scalar* mass,
    scalar* rho
) const
{
    // Total Lagrangian: rho = rho0 / J
    for (label k = begin; k < end; ++k)
    {
        scalar F[4];
        rho[k - begin] = rho_/deformationGradient(grad + 4*k, F);
    }
}


void Foam::spemMaterial::strainEnergyDensity
(
    const label begin,
    const label end,
    const scalar* grad,
    scalar* energy
) const
{
    for (label k = begin; k < end; ++k) energy[k - begin] = 0;
}
