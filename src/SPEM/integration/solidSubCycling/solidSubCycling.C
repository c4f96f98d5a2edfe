#include "solidSubCycling.H"
#include "timeStepControl.H"
#include "Switch.H"
#include "error.H"

#include <cmath>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::solidSubCycling::solidSubCycling(const dictionary& controlDict)
:
    enabled_(controlDict.getOrDefault<Switch>("subCycling", true)),
    maxCo_(timeStepControl::readMaxCo(controlDict)),
    extrapolate_(true)
{
    const word load =
        controlDict.getOrDefault<word>("subCyclingLoad", "extrapolated");
    if (load != "extrapolated" && load != "held")
    {
        FatalIOErrorInFunction(controlDict)
            << "subCyclingLoad " << load << " in " << controlDict.name()
            << ": extrapolated (default) or held" << exit(FatalIOError);
    }
    extrapolate_ = load == "extrapolated";
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::solidSubCycling::active
(
    const scalar fluidStable,
    const scalar solidStable
) const
{
    return
        enabled_ && fluidStable < GREAT && solidStable < GREAT
     && solidStable > 0 && fluidStable >= minSubSteps*solidStable;
}


Foam::label Foam::solidSubCycling::subSteps
(
    const scalar dt,
    const scalar solidStable
) const
{
    // The round-off margin keeps a step of exactly k sub-steps at k
    const scalar n = std::ceil(dt/(maxCo_*solidStable)*(1 - 1e-12));
    return n < 1 ? 1 : label(n);
}


// ************************************************************************* //
