#include "timeStepControl.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::scalar Foam::timeStepControl::stepToWriteTime(const scalar dt) const
{
    const scalar t = runTime_.value() - startTime_;
    const scalar tol = 1e-9*writeInterval_;
    const scalar next =
        (std::floor((t + tol)/writeInterval_) + 1)*writeInterval_;
    const scalar toNext = next - t;
    const scalar n = std::ceil(toNext/dt*(1 - 1e-12));
    return toNext/std::max(n, scalar(1));
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::timeStepControl::timeStepControl(Time& runTime)
:
    runTime_(runTime),
    adjustTimeStep_
    (
        runTime.controlDict().getOrDefault<Switch>("adjustTimeStep", false)
    ),
    maxCo_(runTime.controlDict().getOrDefault<scalar>("maxCo", 0.9)),
    maxDeltaT_(runTime.controlDict().getOrDefault<scalar>("maxDeltaT", GREAT)),
    logInterval_(runTime.controlDict().getOrDefault<label>("logInterval", 100)),
    landOnWriteTimes_
    (
        Time::writeControlNames.getOrDefault
        (
            "writeControl", runTime.controlDict(),
            Time::writeControls::wcTimeStep
        ) == Time::writeControls::wcAdjustableRunTime
    ),
    writeInterval_
    (
        landOnWriteTimes_
      ? runTime.controlDict().get<scalar>("writeInterval")
      : GREAT
    ),
    startTime_(runTime.startTime().value()),
    stableDeltaT_(GREAT)
{
    const dictionary& controls = runTime.controlDict();
    if (!(maxCo_ > 0) || logInterval_ < 1)
    {
        FatalIOErrorInFunction(controls)
            << "maxCo must be positive and logInterval at least 1"
            << exit(FatalIOError);
    }
    if (maxCo_ > 1)
    {
        WarningInFunction
            << "maxCo " << maxCo_ << " > 1: the explicit central-difference"
            << " scheme is unstable above Courant number 1" << nl << endl;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::timeStepControl::check(const scalar stable) const
{
    if (adjustTimeStep_) return;
    if (runTime_.deltaTValue() > maxCo_*stable*(1 + 1e-12))
    {
        FatalIOErrorInFunction(runTime_.controlDict())
            << "deltaT " << runTime_.deltaTValue()
            << " exceeds the stable time step: Courant number "
            << runTime_.deltaTValue()/stable << " > maxCo " << maxCo_
            << " (stable deltaT at Courant number 1: " << stable << ")."
            << nl << "    Reduce deltaT below " << maxCo_*stable
            << " or set adjustTimeStep yes." << exit(FatalIOError);
    }
}


void Foam::timeStepControl::setDeltaT(const scalar stable)
{
    stableDeltaT_ = stable;
    if (!adjustTimeStep_)
    {
        check(stable);
        return;
    }
    const scalar dt = min(maxCo_*stable, maxDeltaT_);
    if (landOnWriteTimes_)
    {
        runTime_.setDeltaT(stepToWriteTime(dt), false);
    }
    else
    {
        runTime_.setDeltaT(dt);
    }
}


// ************************************************************************* //
