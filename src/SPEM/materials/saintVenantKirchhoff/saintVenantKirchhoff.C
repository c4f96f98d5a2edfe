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
    // Plane stress: S is linear in E, so S_zz = 0 leaves the in-plane law
    // with planeLambda exactly; the domain is collapsed if the
    // out-of-plane C_zz = 1 + 2 E_zz it implies is not positive
    const scalar zzRatio = outOfPlaneStrainRatio();
    return parallelAll(begin, end, [&](const label k)
    {
        scalar F[4], S[3], E[3];
        const scalar J = deformationGradient(grad + 4*k, F);
        svk(F, planeLambda_, mu_, S, E);
        scalar* P = stress + 4*k;
        P[0] = F[0]*S[0] + F[1]*S[1];
        P[1] = F[0]*S[1] + F[1]*S[2];
        P[2] = F[2]*S[0] + F[3]*S[1];
        P[3] = F[2]*S[1] + F[3]*S[2];
        return J > 0 && 1 + 2*zzRatio*(E[0] + E[2]) > 0;
    });
}


Foam::scalar Foam::saintVenantKirchhoff::volumeRatio
(
    const scalar J,
    const scalar E[3]
) const
{
    // J_3D = J lambda_zz, lambda_zz^2 = C_zz = 1 + 2 E_zz
    return planeStress()
      ? J*std::sqrt(1 + 2*outOfPlaneStrainRatio()*(E[0] + E[2]))
      : J;
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
        svk(F, planeLambda_, mu_, S, E);
        const scalar J3 = volumeRatio(J, E);
        // sigma = F S F^T / J_3D
        const scalar FS[4] =
        {
            F[0]*S[0] + F[1]*S[1], F[0]*S[1] + F[1]*S[2],
            F[2]*S[0] + F[3]*S[1], F[2]*S[1] + F[3]*S[2]
        };
        scalar* s = sigma6 + 6*(k - begin);
        s[0] = (FS[0]*F[0] + FS[1]*F[1])/J3;
        s[1] = (FS[2]*F[2] + FS[3]*F[3])/J3;
        // S_zz = lambda tr E in plane strain (F_zz = 1), 0 in plane stress
        s[2] = planeStress() ? 0 : lambda_*(E[0] + E[2])/J;
        s[3] = (FS[0]*F[2] + FS[1]*F[3])/J3;
        s[4] = 0;
        s[5] = 0;
        pressure[k - begin] = -(s[0] + s[1] + s[2])/3;
    }
}


void Foam::saintVenantKirchhoff::density
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* rho
) const
{
    for (label k = begin; k < end; ++k)
    {
        scalar F[4], S[3], E[3];
        const scalar J = deformationGradient(grad + 4*k, F);
        svk(F, planeLambda_, mu_, S, E);
        rho[k - begin] = rho_/volumeRatio(J, E);
    }
}


Foam::scalar Foam::saintVenantKirchhoff::longitudinalModulus
(
    const scalar F[4]
) const
{
    // Principal stretches squared, the eigenvalues of C = F^T F
    const scalar Cxx = F[0]*F[0] + F[2]*F[2];
    const scalar Cyy = F[1]*F[1] + F[3]*F[3];
    const scalar Cxy = F[0]*F[1] + F[2]*F[3];
    const scalar mean = 0.5*(Cxx + Cyy);
    const scalar radius = std::sqrt(0.25*(Cxx - Cyy)*(Cxx - Cyy) + Cxy*Cxy);
    const scalar trE = mean - 1;
    // Longitudinal modulus along each principal direction (see header):
    // (lambda + 2 mu) l^4 + S_i l^2, S_i = lambda tr E + mu (l^2 - 1)
    scalar modulus = 0;
    for (const scalar l2 : {mean + radius, mean - radius})
    {
        const scalar S = planeLambda_*trE + mu_*(l2 - 1);
        modulus = std::max(modulus, (planeLambda_ + 2*mu_)*l2*l2 + S*l2);
    }
    return modulus;
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
        svk(F, planeLambda_, mu_, S, E);
        // With E_zz eliminated (plane stress) the in-plane law's energy
        const scalar trE = E[0] + E[2];
        energy[k - begin] = 0.5*planeLambda_*trE*trE
          + mu_*(E[0]*E[0] + 2*E[1]*E[1] + E[2]*E[2]);
    }
}
