#include "weaklyCompressibleNewtonian.H"
#include "parallelLoop.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(weaklyCompressibleNewtonian, 0);
    addToRunTimeSelectionTable
    (
        spemMaterial,
        weaklyCompressibleNewtonian,
        dictionary
    );
}


namespace
{

// initialPressure: zero (default) or hydrostatic
bool readHydrostaticStart(const Foam::word& name, const Foam::dictionary& dict)
{
    using namespace Foam;
    const word start = dict.getOrDefault<word>("initialPressure", "zero");
    if (start != "zero" && start != "hydrostatic")
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'initialPressure " << start << "' of region " << name
            << ": expected zero (the default) or hydrostatic"
            << exit(FatalIOError);
    }
    return start == "hydrostatic";
}

} // End anonymous namespace


Foam::weaklyCompressibleNewtonian::weaklyCompressibleNewtonian
(
    const word& name,
    const dictionary& dict
)
:
    spemMaterial(name, dict),
    c_(readChecked("c", saneRange::soundSpeed)),
    mu_
    (
        dict.found("mu") ? readChecked("mu", saneRange::viscosity) : 0
    ),
    hydrostaticStart_(readHydrostaticStart(name, dict)),
    bulkViscosity_
    (
        dict.found("bulkViscosity")
      ? readChecked("bulkViscosity", saneRange::bulkViscosity)
      : 0
    )
{}


namespace
{

//- The fluid stress of the domains of the lanes of V from k on (simdLanes.H:
//  scalar, or simd::pair for k and k + 1), eqs. 6-10; with Bulk the bulk
//  viscous stress b1RhoC l div(v) too (taken from the pressure, so that
//  without it the arithmetic is that of eqs. 7-10 alone)
template<bool Bulk, class V>
inline void fluidStressOf
(
    const Foam::label k,
    const Foam::scalar* grad, const Foam::scalar* area,
    const Foam::scalar* mass, Foam::scalar* stress,
    const Foam::scalar c2, const Foam::scalar rho0, const Foam::scalar twoMu,
    const Foam::scalar b1RhoC
)
{
    using namespace Foam;
    // Entry i of each lane's domain in field, stride entries per domain
    const auto ofDomain = [&]
    (
        const scalar* field, const label stride, const label i
    )
    {
        return simd::gather<V>
        (
            [&](const label l) { return field[stride*(k + l) + i]; }
        );
    };
    V g[4];
    for (label i = 0; i < 4; ++i) g[i] = ofDomain(grad, 4, i);
    const V A = ofDomain(area, 1, 0);
    const V div = g[0] + g[3];
    V p = c2*(ofDomain(mass, 1, 0)/A - rho0);                   // eq. 7
    if constexpr (Bulk)
    {
        p -= b1RhoC*weaklyCompressibleNewtonian::bulkViscosityLength(A)*div;
    }
    const V div3 = div/3.0;
    V s[4];
    s[0] = -p + twoMu*(g[0] - div3);                             // eqs. 9-10
    s[1] = 0.5*twoMu*(g[1] + g[2]);
    s[2] = s[1];
    s[3] = -p + twoMu*(g[3] - div3);
    for (label i = 0; i < 4; ++i)
    {
        simd::scatter
        (
            s[i], [&](const label l) -> scalar& { return stress[4*(k + l) + i]; }
        );
    }
}


//- fluidStressOf() of domains [begin, end), two at a time
template<bool Bulk>
void fluidStress
(
    const Foam::label begin, const Foam::label end,
    const Foam::scalar* grad, const Foam::scalar* area,
    const Foam::scalar* mass, Foam::scalar* stress,
    const Foam::scalar c2, const Foam::scalar rho0, const Foam::scalar twoMu,
    const Foam::scalar b1RhoC
)
{
    using namespace Foam;
    simd::parallelForPairs(begin, end, [&](const auto tag, const label k)
    {
        fluidStressOf<Bulk, typename decltype(tag)::type>
        (
            k, grad, area, mass, stress, c2, rho0, twoMu, b1RhoC
        );
    });
}

} // End anonymous namespace


bool Foam::weaklyCompressibleNewtonian::stress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* stress
) const
{
    const scalar c2 = c_*c_, b1RhoC = bulkViscosity_*rho_*c_;
    if (bulkViscosity_ > 0)
    {
        fluidStress<true>
        (
            begin, end, grad, area, mass, stress, c2, rho_, 2*mu_, b1RhoC
        );
    }
    else
    {
        fluidStress<false>
        (
            begin, end, grad, area, mass, stress, c2, rho_, 2*mu_, b1RhoC
        );
    }
    return true;
}


void Foam::weaklyCompressibleNewtonian::cauchyStress
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* sigma6,
    scalar* pressure
) const
{
    for (label k = begin; k < end; ++k)
    {
        const scalar* g = grad + 4*k;
        const scalar p = c_*c_*(mass[k]/area[k] - rho_);
        const scalar div = g[0] + g[3];
        const scalar div3 = div/3;
        // The bulk viscous stress is in the tensor, not in the pressure
        // (the thermodynamic one, eq. 7)
        scalar pq = p;
        if (bulkViscosity_ > 0)
        {
            pq -= bulkViscosity_*rho_*c_*bulkViscosityLength(area[k])*div;
        }
        scalar* s = sigma6 + 6*(k - begin);
        s[0] = -pq + 2*mu_*(g[0] - div3);
        s[1] = -pq + 2*mu_*(g[3] - div3);
        s[2] = -pq - 2*mu_*div3;
        s[3] = mu_*(g[1] + g[2]);
        s[4] = 0;
        s[5] = 0;
        pressure[k - begin] = p;
    }
}


void Foam::weaklyCompressibleNewtonian::density
(
    const label begin, const label end, const scalar* grad,
    const scalar* area, const scalar* mass, scalar* rho
) const
{
    for (label k = begin; k < end; ++k) rho[k - begin] = mass[k]/area[k];
}
