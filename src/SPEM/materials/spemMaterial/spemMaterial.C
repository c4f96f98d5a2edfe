#include "spemMaterial.H"

namespace Foam
{
    defineTypeNameAndDebug(spemMaterial, 0);
    defineRunTimeSelectionTable(spemMaterial, dictionary);
}


Foam::scalar Foam::spemMaterial::readChecked
(
    const word& key,
    const valueRange& range
) const
{
    const scalar value = dict_.get<scalar>(key);
    if (!range.holds(value))
    {
        outOfRange(dict_, key, value, range, "region " + name_ + ':');
    }
    return value;
}


Foam::spemMaterial::spemMaterial(const word& name, const dictionary& dict)
:
    name_(name),
    dict_(dict),
    rho_(readChecked("rho", saneRange::density))
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
