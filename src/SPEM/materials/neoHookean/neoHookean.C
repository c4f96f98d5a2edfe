#include "neoHookean.H"
#include "parallelLoop.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(neoHookean, 0);
    addToRunTimeSelectionTable(spemMaterial, neoHookean, dictionary);
}


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using Foam::scalar;

//- Newton iterations of the out-of-plane stretch stop once the correction
//  is below this: the next one, of order its square (quadratic
//  convergence, f''/(2 f') <= 1 for lambda >= 0), is below round-off
constexpr scalar logStretchTolerance = 1e-8;

//- Safeguard on the Newton iterations (4 reach round-off at strains of
//  order 1)
constexpr int maxLogStretchIterations = 20;


//- Plane stress: ln lambda_zz at the in-plane ln J, the root of
//      f(s) = mu (e^{2s} - 1) + lambda (ln J + s) = 0     (P_zz lambda_zz = 0)
//  by Newton (see neoHookean.H). A local function rather than a member
//  so that the hot loops inline it (a member of a shared library is
//  called through the PLT).
inline scalar planeStressLogStretch
(
    const scalar lnJ,
    const scalar lambda,
    const scalar mu
)
{
    // Start from the root of the quadratic expansion of f,
    // (lambda + 2 mu) s + 2 mu s^2 = -lambda ln J, to second order: one
    // Newton iteration instead of two from the linear s1 at strains of
    // 1e-3 (3 from 0.1 to 0.5, 4 at 1)
    const scalar s1 = -lambda*lnJ/(lambda + 2*mu);
    scalar s = s1 - 2*mu*s1*s1/(lambda + 2*mu);
    for (int it = 0; it < maxLogStretchIterations; ++it)
    {
        const scalar lz2 = std::exp(2*s);
        const scalar ds = (mu*(lz2 - 1) + lambda*(lnJ + s))/(2*mu*lz2 + lambda);
        s -= ds;
        if (std::abs(ds) < logStretchTolerance) break;
    }
    return s;
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::scalar Foam::neoHookean::outOfPlaneLogStretch(const scalar lnJ) const
{
    return planeStress() ? planeStressLogStretch(lnJ, lambda_, mu_) : 0;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::neoHookean::neoHookean(const word& name, const dictionary& dict)
:
    elasticSolid(name, dict)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::neoHookean::stress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* stress
) const
{
    const bool planeStress = this->planeStress();
    const scalar lambda = lambda_, mu = mu_;
    return parallelAll(begin, end, [&](const label k)
    {
        scalar F[4];
        const scalar J = deformationGradient(grad + 4*k, F);
        scalar* P = stress + 4*k;
        if (!(J > 0))
        {
            P[0] = P[1] = P[2] = P[3] = 0;
            return false;
        }
        const scalar lnJ = std::log(J);
        // ln J_3D = ln J + ln lambda_zz
        const scalar lnJ3 =
            planeStress ? lnJ + planeStressLogStretch(lnJ, lambda, mu) : lnJ;
        // F^-T = cofactor(F)/J (the in-plane block of the 3D F^-T)
        const scalar FinvT[4] = {F[3]/J, -F[2]/J, -F[1]/J, F[0]/J};
        const scalar c = lambda*lnJ3 - mu;
        for (label i = 0; i < 4; ++i) P[i] = mu*F[i] + c*FinvT[i];
        return true;
    });
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
        const scalar lnLz = outOfPlaneLogStretch(lnJ);
        const scalar lnJ3 = lnJ + lnLz;
        const scalar J3 = J*std::exp(lnLz);
        // sigma = (mu (B - I) + lambda ln J_3D I)/J_3D, B = F F^T with
        // B_zz = lambda_zz^2. sigma_zz vanishes in plane stress up to the
        // convergence of its Newton solve: computed, not set to 0.
        scalar* s = sigma6 + 6*(k - begin);
        s[0] = (mu_*(F[0]*F[0] + F[1]*F[1] - 1) + lambda_*lnJ3)/J3;
        s[1] = (mu_*(F[2]*F[2] + F[3]*F[3] - 1) + lambda_*lnJ3)/J3;
        s[2] = (mu_*(std::exp(2*lnLz) - 1) + lambda_*lnJ3)/J3;
        s[3] = mu_*(F[0]*F[2] + F[1]*F[3])/J3;
        s[4] = 0;
        s[5] = 0;
        pressure[k - begin] = -(s[0] + s[1] + s[2])/3;
    }
}


void Foam::neoHookean::density
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* rho
) const
{
    // rho0/J_3D
    for (label k = begin; k < end; ++k)
    {
        scalar F[4];
        const scalar J = deformationGradient(grad + 4*k, F);
        rho[k - begin] = rho_/(J*std::exp(outOfPlaneLogStretch(std::log(J))));
    }
}


Foam::scalar Foam::neoHookean::longitudinalModulus(const scalar F[4]) const
{
    const scalar J = F[0]*F[3] - F[1]*F[2];
    const scalar lnJ = std::log(J);
    // Largest squared stretch: the larger eigenvalue of B = F F^T
    const scalar trB = F[0]*F[0] + F[1]*F[1] + F[2]*F[2] + F[3]*F[3];
    const scalar lMax2 =
        0.5*(trB + std::sqrt(std::max(trB*trB - 4*J*J, scalar(0))));
    // Longitudinal modulus along it (see header), at least the transverse
    // mu lMax2
    scalar longitudinal;
    if (planeStress())
    {
        // lambda_zz^2 from the small-strain ln lambda_zz, the first Newton
        // step from lambda_zz = 1: f being convex it is at or above the
        // root, and the modulus grows with lambda_zz: a bound from above
        const scalar lz2 = std::exp(-2*lambda_*lnJ/(lambda_ + 2*mu_));
        longitudinal = mu_*lMax2
          + mu_*lz2*(3*lambda_ + 2*mu_*lz2)/(lambda_ + 2*mu_*lz2);
    }
    else
    {
        longitudinal = lambda_*(1 - lnJ) + mu_*(1 + lMax2);
    }
    return std::max(longitudinal, mu_*lMax2);
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
        const scalar lnLz = outOfPlaneLogStretch(lnJ);
        const scalar lnJ3 = lnJ + lnLz;
        const scalar trC =
            F[0]*F[0] + F[1]*F[1] + F[2]*F[2] + F[3]*F[3] + std::exp(2*lnLz);
        energy[k - begin] =
            0.5*mu_*(trC - 3) - mu_*lnJ3 + 0.5*lambda_*lnJ3*lnJ3;
    }
}
