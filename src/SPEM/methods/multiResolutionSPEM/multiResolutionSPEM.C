#include "multiResolutionSPEM.H"
#include "checkKeywords.H"
#include "timeStepControl.H"
#include "addToRunTimeSelectionTable.H"

#include <cmath>

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

    // Measured (issue 15): cylinderWaterExit nx 8 with the cylinder held
    // still, to 1.2 s; the largest interface node speed was 0.20 and
    // 0.23 m/s at maxCo 0.5 and 0.6, 0.42 at 0.7, 0.60 at 0.8, 2.09 at
    // 1.0 (SPEM: 0.09 m/s at 0.8, quiet to 1.2). 0.45 is 1.5 times below
    // the onset, as the default 0.8 is for SPEM
    const scalar maxCo = timeStepControl::readMaxCo(c.runTime.controlDict());
    if (maxCo > maxQuietCo)
    {
        WarningInFunction
            << "maxCo " << maxCo << " with multiResolutionSPEM: the"
            << " element-particle interface of refined particles starts to"
            << " oscillate from Courant number 0.7 (measured; SPEM's from"
            << " 1.2). Set maxCo " << maxQuietCo << " in "
            << c.runTime.controlDict().name() << " for a quiet interface,"
            << " at about " << maxCo/maxQuietCo << " times the steps"
            << nl << endl;
    }
}


// ************************************************************************* //
