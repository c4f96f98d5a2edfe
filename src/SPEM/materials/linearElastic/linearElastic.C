#include "linearElastic.H"
#include "parallelLoop.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(linearElastic, 0);
    addToRunTimeSelectionTable(spemMaterial, linearElastic, dictionary);
}


Foam::linearElastic::linearElastic(const word& name, const dictionary& dict)
:
    elasticSolid(name, dict)
{}


bool Foam::linearElastic::stress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* stress
) const
{
    const scalar lambda = planeLambda_, mu = mu_;
    parallelFor(begin, end, [&](const label k)
    {
        const scalar* g = grad + 4*k;
        scalar* s = stress + 4*k;
        const scalar exy = 0.5*(g[1] + g[2]);
        const scalar volumetric = lambda*(g[0] + g[3]);
        s[0] = volumetric + 2*mu*g[0];
        s[1] = 2*mu*exy;
        s[2] = s[1];
        s[3] = volumetric + 2*mu*g[3];
    });
    return true;
}


void Foam::linearElastic::cauchyStress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* sigma6,
    scalar* pressure
) const
{
    for (label k = begin; k < end; ++k)
    {
        const scalar* g = grad + 4*k;
        scalar* s = sigma6 + 6*(k - begin);
        const scalar tr = g[0] + g[3];
        const scalar volumetric = planeLambda_*tr;
        s[0] = volumetric + 2*mu_*g[0];
        s[1] = volumetric + 2*mu_*g[3];
        s[2] = planeStress() ? 0 : lambda_*tr;
        s[3] = mu_*(g[1] + g[2]);
        s[4] = 0;
        s[5] = 0;
        pressure[k - begin] = -(s[0] + s[1] + s[2])/3;
    }
}


void Foam::linearElastic::density
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* rho
) const
{
    // Small strain: rho0 (1 - tr eps), eps_zz included (plane stress)
    const scalar zzRatio = outOfPlaneStrainRatio();
    for (label k = begin; k < end; ++k)
    {
        const scalar* g = grad + 4*k;
        rho[k - begin] = rho_*(1 - (1 + zzRatio)*(g[0] + g[3]));
    }
}


void Foam::linearElastic::strainEnergyDensity
(
    const label begin, const label end, const scalar* grad, scalar* energy
) const
{
    // With eps_zz eliminated (plane stress) the energy of the in-plane law
    for (label k = begin; k < end; ++k)
    {
        const scalar* g = grad + 4*k;
        const scalar exy = 0.5*(g[1] + g[2]);
        const scalar tr = g[0] + g[3];
        energy[k - begin] =
            0.5*planeLambda_*tr*tr + mu_*(g[0]*g[0] + g[3]*g[3] + 2*exy*exy);
    }
}
