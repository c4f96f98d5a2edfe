#include "restartTime.H"
#include "argList.H"
#include "Switch.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::restartTime::restartTime
(
    const word& controlDictName,
    const argList& args
)
:
    Time(controlDictName, args)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::restartTime::fallback() const
{
    return controlDict().getOrDefault<Switch>("restartFallback", false);
}


bool Foam::restartTime::namesStartState(const error& err) const
{
    const std::string dir = timePath();
    const auto inDir = [&dir](const std::string& text)
    {
        return text.find(dir + '/') != std::string::npos;
    };
    if (inDir(err.message())) return true;
    const IOerror* io = dynamic_cast<const IOerror*>(&err);
    return io && inDir(io->ioFileName());
}


bool Foam::restartTime::previousTime(instant& previous) const
{
    const instantList times = findTimes(path(), constant());
    bool found = false;
    for (const instant& t : times)
    {
        // Sorted by value; the start time itself is not a fallback
        if (t.value() >= value() - 1e-12*max(mag(value()), 1)) break;
        previous = t;
        found = true;
    }
    if (!found && value() > 0)
    {
        // The initial state (the mesh of constant/): a run from 0
        previous = instant(0, "0");
        found = true;
    }
    return found;
}


void Foam::restartTime::startFrom(const instant& t)
{
    // Time::setControls() takes the step from uniform/time only under
    // adjustTimeStep; setTime() always does
    const scalar controlDeltaT = deltaT_;
    setTime(t, 0);
    if (!controlDict().getOrDefault<Switch>("adjustTimeStep", false))
    {
        deltaT_ = controlDeltaT;
    }
    deltaTSave_ = deltaT_;
    startTime_ = value();
    startTimeIndex_ = timeIndex_;
}


// ************************************************************************* //
