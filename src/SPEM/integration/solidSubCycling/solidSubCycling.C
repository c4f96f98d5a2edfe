#include "solidSubCycling.H"
#include "timeStepControl.H"
#include "Switch.H"
#include "error.H"

#include <cmath>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::solidSubCycling::solidSubCycling(const dictionary& controlDict)
:
    enabled_(controlDict.getOrDefault<Switch>("subCycling", true)),
    maxCo_
    (
        min
        (
            controlDict.getOrDefault<scalar>("subCyclingMaxCo", defaultMaxCo),
            timeStepControl::readMaxCo(controlDict)
        )
    ),
    load_(elementModel::subCycleLoad::interpolated),
    maxSteps_(timeStepControl::readMaxSteps(controlDict)),
    stepMaxCo_(timeStepControl::readMaxCo(controlDict))
{
    const scalar co =
        controlDict.getOrDefault<scalar>("subCyclingMaxCo", defaultMaxCo);
    if (!(co > 0 && co <= 1))
    {
        FatalIOErrorInFunction(controlDict)
            << "subCyclingMaxCo " << co << " in " << controlDict.name()
            << ": the Courant number of the solids' sub-steps must lie in"
            << " (0, 1] (default " << defaultMaxCo << ")"
            << exit(FatalIOError);
    }
    const word load =
        controlDict.getOrDefault<word>("subCyclingLoad", "interpolated");
    if (load == "extrapolated")
    {
        load_ = elementModel::subCycleLoad::extrapolated;
    }
    else if (load == "held")
    {
        load_ = elementModel::subCycleLoad::held;
    }
    else if (load != "interpolated")
    {
        FatalIOErrorInFunction(controlDict)
            << "subCyclingLoad " << load << " in " << controlDict.name()
            << ": interpolated (default), extrapolated or held"
            << exit(FatalIOError);
    }
}


const char* Foam::solidSubCycling::loadName() const
{
    switch (load_)
    {
        case elementModel::subCycleLoad::held: return "held";
        case elementModel::subCycleLoad::extrapolated: return "extrapolated";
        default: return "interpolated";
    }
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
