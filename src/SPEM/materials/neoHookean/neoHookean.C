#include "neoHookean.H"
#include "parallelLoop.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(neoHookean, 0);
    addToRunTimeSelectionTable(spemMaterial, neoHookean, dictionary);
}


Foam::neoHookean::neoHookean(const word& name, const dictionary& dict)
:
    elasticSolid(name, dict)
{}


bool Foam::neoHookean::stress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* stress
) const
{
    bool ok = true;
    #pragma omp parallel for schedule(static) reduction(&&: ok) if(end - begin > minParallelLoop)
    for (label k = begin; k < end; ++k)
    {
        scalar F[4];
        const scalar J = deformationGradient(grad + 4*k, F);
        scalar* P = stress + 4*k;
        if (!(J > 0))
        {
            ok = false;
            P[0] = P[1] = P[2] = P[3] = 0;
            continue;
        }
        // F^-T = cofactor(F)/J
        const scalar FinvT[4] = {F[3]/J, -F[2]/J, -F[1]/J, F[0]/J};
        const scalar c = lambda_*std::log(J) - mu_;
        for (label i = 0; i < 4; ++i) P[i] = mu_*F[i] + c*FinvT[i];
    }
    return ok;
}


void Foam::neoHookean::cauchyStress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* sigma6,
    scalar* pressure
) const
{
    for (label k = begin; k < end; ++k)
    {
        scalar F[4];
        const scalar J = deformationGradient(grad + 4*k, F);
        const scalar lnJ = std::log(J);
        // sigma = (mu (B - I) + lambda ln J I)/J, B = F F^T
        scalar* s = sigma6 + 6*(k - begin);
        s[0] = (mu_*(F[0]*F[0] + F[1]*F[1] - 1) + lambda_*lnJ)/J;
        s[1] = (mu_*(F[2]*F[2] + F[3]*F[3] - 1) + lambda_*lnJ)/J;
        s[2] = lambda_*lnJ/J;
        s[3] = mu_*(F[0]*F[2] + F[1]*F[3])/J;
        s[4] = 0;
        s[5] = 0;
        pressure[k - begin] = -(s[0] + s[1] + s[2])/3;
    }
}


void Foam::neoHookean::strainEnergyDensity
(
    const label begin, const label end, const scalar* grad, scalar* energy
) const
{
    for (label k = begin; k < end; ++k)
    {
        scalar F[4];
        const scalar J = deformationGradient(grad + 4*k, F);
        const scalar lnJ = std::log(J);
        const scalar trC = F[0]*F[0] + F[1]*F[1] + F[2]*F[2] + F[3]*F[3];
        energy[k - begin] =
            0.5*mu_*(trC - 2) - mu_*lnJ + 0.5*lambda_*lnJ*lnJ;
    }
}
