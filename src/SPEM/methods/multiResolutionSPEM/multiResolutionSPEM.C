#include "multiResolutionSPEM.H"
#include "checkKeywords.H"
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
}


// ************************************************************************* //
