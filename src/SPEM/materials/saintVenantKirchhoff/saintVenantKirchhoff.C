#include "saintVenantKirchhoff.H"
#include "parallelLoop.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(saintVenantKirchhoff, 0);
    addToRunTimeSelectionTable(spemMaterial, saintVenantKirchhoff, dictionary);
}

namespace
{

//- Second Piola-Kirchhoff stress S (xx, xy, yy) and Green-Lagrange strain
//  E of the deformation gradient F
inline void svk
(
    const Foam::scalar F[4], const Foam::scalar lambda, const Foam::scalar mu,
    Foam::scalar S[3], Foam::scalar E[3]
)
{
    E[0] = 0.5*(F[0]*F[0] + F[2]*F[2] - 1);
    E[1] = 0.5*(F[0]*F[1] + F[2]*F[3]);
    E[2] = 0.5*(F[1]*F[1] + F[3]*F[3] - 1);
    const Foam::scalar trE = E[0] + E[2];
    S[0] = lambda*trE + 2*mu*E[0];
    S[1] = 2*mu*E[1];
    S[2] = lambda*trE + 2*mu*E[2];
}

} // End anonymous namespace


Foam::saintVenantKirchhoff::saintVenantKirchhoff
(
    const word& name,
    const dictionary& dict
)
:
    elasticSolid(name, dict)
{}


bool Foam::saintVenantKirchhoff::stress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* stress
) const
{
    bool ok = true;
    #pragma omp parallel for schedule(static) reduction(&&: ok) if(end - begin > minParallelLoop)
    for (label k = begin; k < end; ++k)
    {
        scalar F[4], S[3], E[3];
        const scalar J = deformationGradient(grad + 4*k, F);
        ok = ok && J > 0;
        svk(F, lambda_, mu_, S, E);
        scalar* P = stress + 4*k;
        P[0] = F[0]*S[0] + F[1]*S[1];
        P[1] = F[0]*S[1] + F[1]*S[2];
        P[2] = F[2]*S[0] + F[3]*S[1];
        P[3] = F[2]*S[1] + F[3]*S[2];
    }
    return ok;
}


void Foam::saintVenantKirchhoff::cauchyStress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* sigma6,
    scalar* pressure
) const
{
    for (label k = begin; k < end; ++k)
    {
        scalar F[4], S[3], E[3];
        const scalar J = deformationGradient(grad + 4*k, F);
        svk(F, lambda_, mu_, S, E);
        // sigma = F S F^T / J
        const scalar FS[4] =
        {
            F[0]*S[0] + F[1]*S[1], F[0]*S[1] + F[1]*S[2],
            F[2]*S[0] + F[3]*S[1], F[2]*S[1] + F[3]*S[2]
        };
        scalar* s = sigma6 + 6*(k - begin);
        s[0] = (FS[0]*F[0] + FS[1]*F[1])/J;
        s[1] = (FS[2]*F[2] + FS[3]*F[3])/J;
        s[2] = lambda_*(E[0] + E[2])/J;
        s[3] = (FS[0]*F[2] + FS[1]*F[3])/J;
        s[4] = 0;
        s[5] = 0;
        pressure[k - begin] = -(s[0] + s[1] + s[2])/3;
    }
}


void Foam::saintVenantKirchhoff::strainEnergyDensity
(
    const label begin, const label end, const scalar* grad, scalar* energy
) const
{
    for (label k = begin; k < end; ++k)
    {
        scalar F[4], S[3], E[3];
        deformationGradient(grad + 4*k, F);
        svk(F, lambda_, mu_, S, E);
        const scalar trE = E[0] + E[2];
        energy[k - begin] = 0.5*lambda_*trE*trE
          + mu_*(E[0]*E[0] + 2*E[1]*E[1] + E[2]*E[2]);
    }
}
