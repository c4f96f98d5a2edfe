#include "multiResolutionSPEM.H"
#include "checkKeywords.H"
#include "timeStepControl.H"
#include "addToRunTimeSelectionTable.H"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace
{

//- x to three significant digits, for the log
std::string brief(const Foam::scalar x)
{
    std::ostringstream os;
    os << std::setprecision(3) << x;
    return os.str();
}

} // End anonymous namespace

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace spemMethods
{
    defineTypeNameAndDebug(multiResolutionSPEM, 0);
    addToRunTimeSelectionTable(spemMethod, multiResolutionSPEM, dictionary);
}
}


// * * * * * * * * * * * * * Static Member Functions * * * * * * * * * * * * //

Foam::scalar Foam::spemMethods::multiResolutionSPEM::readRefinedRadiusRatio
(
    const dictionary& schemes
)
{
    // The paper's range (sect. 2.3.1, after eq. 22); 1/sqrt(3) lies in it
    const valueRange paperRange
    {
        0.5, 0.6, "(R_i/R_M)",
        "the paper's 0.5-0.6 R_M (eq. 22); 1/sqrt(3), the default, gives"
        " the three refined particles the element's area"
    };
    return getCheckedOrDefault
    (
        schemes.subOrEmptyDict("conversion"), "refinedRadiusRatio",
        1/std::sqrt(3.0), paperRange
    );
}


Foam::scalar Foam::spemMethods::multiResolutionSPEM::oscillationCo
(
    const scalar phi
)
{
    // Measured (issue 15): cylinderWaterExit nx 8 with the cylinder held
    // still, to 1.2 s, the largest node speed over the writes 0.1 s apart
    // (quiet: 0.16-0.19 m/s; SPEM 0.08 at maxCo 0.8, quiet to 1.2). The
    // first maxCo at which it rose above about 0.25 m/s, for each phi:
    //   phi 0     noisy at every maxCo tried (0.61 m/s at 0.3)
    //   phi 0.05  0.19 at 0.45, 0.51 at 0.6
    //   phi 0.1   0.23 at 0.6, 0.42 at 0.7 (0.57 at 0.8, 2.09 at 1.0)
    //   phi 0.2   0.16 at 0.8, 0.28 at 0.9
    //   phi 0.3   0.16 at 0.9, 0.29 at 1.0
    //   phi 0.5   0.16 at 1.1, 0.41 at 1.2
    //   phi 1     0.20 at 1.2 (onset not reached; taken as 1.2)
    // and between them linearly
    static const scalar phis[] = {0, 0.05, 0.1, 0.2, 0.3, 0.5};
    static const scalar onsets[] = {0, 0.5, 0.7, 0.9, 1.0, 1.2};
    constexpr label n = sizeof(phis)/sizeof(phis[0]);
    if (!(phi > phis[0])) return onsets[0];
    for (label k = 1; k < n; ++k)
    {
        if (phi <= phis[k])
        {
            const scalar w = (phi - phis[k - 1])/(phis[k] - phis[k - 1]);
            return onsets[k - 1] + w*(onsets[k] - onsets[k - 1]);
        }
    }
    return onsets[n - 1];
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemMethods::multiResolutionSPEM::multiResolutionSPEM
(
    const spemCase& c,
    PtrList<spemMaterial>& materials
)
:
    SPEM(c, materials, readRefinedRadiusRatio(c.schemes))
{
    Info<< "    multi-resolution: each converted element becomes 3 refined"
        << " particles of radius " << refinedRadiusRatio_ << " R_M"
        << " (eqs. 19-22), spacing " << convertedSpacing() << " m" << nl;

    // The interface's Courant limit depends on phi of eq. (26); maxCo
    // 1.5 times below the onset is quiet, as the default 0.8 is for SPEM
    // (the coupling itself is made with the particle half, later)
    const scalar phi =
        elementParticleCoupling::readVelocityCorrection(c.schemes);
    const scalar onset = oscillationCo(phi);
    const scalar quiet = maxQuietCo(phi);
    const scalar maxCo = timeStepControl::readMaxCo(c.runTime.controlDict());
    if (onset <= 0)
    {
        WarningInFunction
            << "coupling/interfaceVelocityCorrection 0 with"
            << " multiResolutionSPEM: without eq. (26)'s correction the"
            << " element-particle interface of refined particles oscillates"
            << " at every Courant number measured (0.3 included). Set"
            << " interfaceVelocityCorrection 0.1 (the default) or 0.5 in "
            << c.schemes.name() << nl << endl;
    }
    else if (maxCo > quiet)
    {
        WarningInFunction
            << "maxCo " << brief(maxCo).c_str() << " with"
            << " multiResolutionSPEM and coupling/interfaceVelocityCorrection "
            << brief(phi).c_str() << ": the element-particle interface of"
            << " refined particles starts to oscillate from Courant number "
            << brief(onset).c_str() << " (measured; from "
            << brief(oscillationCo(0.5)).c_str() << " with"
            << " interfaceVelocityCorrection 0.5, SPEM's from 1.2). For a"
            << " quiet interface set maxCo " << brief(quiet).c_str()
            << " in " << c.runTime.controlDict().name() << " (about "
            << brief(maxCo/quiet).c_str() << " times the steps), or a"
            << " larger interfaceVelocityCorrection in " << c.schemes.name()
            << " (0.5: quiet to maxCo " << brief(maxQuietCo(0.5)).c_str()
            << "; its effect on the results: multiResolutionSPEM.H)"
            << nl << endl;
    }
}


// ************************************************************************* //
