/*---------------------------------------------------------------------------*\
Application
    spemFoam

Description
    Explicit solver of the smoothed particle element method (SPEM) for
    fluid-structure interaction with free surfaces: fluids and solids on a
    triangle mesh with the edge-based smoothed FEM, central-difference time
    integration (paper sect. 2.1); with method SPH the fluid as WCSPH
    particles (sect. 2.2).

Usage
    spemFoam [-case dir]

    Reads constant/spemMesh (from spemMeshConvert), constant/spemProperties,
    constant/g, system/spemSchemes (see spemModel, spemMethod) and
    system/controlDict (the time step: see timeStepControl; Courant number
    1 is the elements' fastest wave over their smallest altitude and the
    particles' h/(c + |v|)).
    Writes <time>/spem/ (restart state), VTK/<case>.pvd (ParaView series)
    and postProcessing/ (function objects of controlDict `functions`).

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "restartTime.H"
#include "spemModel.H"
#include "timeStepControl.H"

#include <memory>
#include <type_traits>

using namespace Foam;

namespace
{
    //- The case read at the start time or, under restartFallback, at the
    //  latest earlier time whose state reads (see restartTime)
    std::unique_ptr<spemModel> readCase(restartTime& runTime)
    {
        if (!runTime.fallback()) return std::make_unique<spemModel>(runTime);

        const bool wasThrowing = FatalError.throwExceptions();
        const bool wasIOThrowing = FatalIOError.throwExceptions();
        const auto restore = [&]()
        {
            FatalError.throwExceptions(wasThrowing);
            FatalIOError.throwExceptions(wasIOThrowing);
        };
        for (;;)
        {
            // The error of this attempt, if it is the start state's
            std::unique_ptr<error> failure;
            // Any other error stops as it would have; exit() is not
            // virtual, so each type is kept as itself (IOerror prints its
            // file)
            const auto keepOrExit = [&](auto& err)
            {
                if (!runTime.namesStartState(err))
                {
                    restore();
                    err.throwExceptions(false);
                    err.exit(1);
                }
                failure =
                    std::make_unique<std::decay_t<decltype(err)>>(err);
            };
            try
            {
                auto model = std::make_unique<spemModel>(runTime);
                restore();
                return model;
            }
            catch (IOerror& err) { keepOrExit(err); }
            catch (error& err) { keepOrExit(err); }
            // The file and line of a reader's error (a truncated file)
            std::string cause = failure->message();
            if (const auto* io = dynamic_cast<const IOerror*>(failure.get()))
            {
                cause += "\n    file: " + io->ioFileName();
                if (io->ioStartLineNumber() >= 0)
                {
                    cause +=
                        " at line " + std::to_string(io->ioStartLineNumber());
                }
            }
            instant previous;
            if (!runTime.previousTime(previous))
            {
                restore();
                FatalErrorInFunction
                    << "restartFallback: the state of time "
                    << runTime.timeName() << " cannot be read and no time"
                    << " is before it:" << nl << cause.c_str()
                    << exit(FatalError);
            }
            WarningInFunction
                << "restartFallback: the state of time " << runTime.timeName()
                << " cannot be read:" << nl << cause.c_str()
                << nl << "    Falling back to time " << previous.name()
                << " (the latest time before it). Time "
                << runTime.timeName() << " is left as it is until this run"
                << " writes it again." << nl << endl;
            runTime.startFrom(previous);
        }
    }
}

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Explicit smoothed particle element method (SPEM) solver for"
        " fluid-structure interaction with free surfaces"
    );
    argList::noParallel();

    #include "setRootCase.H"
    timeStepControl::checkBeforeTime(args.path());
    Info<< "Create time\n" << endl;
    restartTime runTime(Time::controlDictName, args);

    // controlDict first: a bad entry stops before the case is read
    auto timeStep = std::make_unique<timeStepControl>(runTime);
    const scalar requestedStart = runTime.value();
    const std::unique_ptr<spemModel> modelPtr = readCase(runTime);
    spemModel& model = *modelPtr;
    if (runTime.value() != requestedStart)
    {
        // It measures the write times from the start time
        timeStep = std::make_unique<timeStepControl>(runTime);
    }

    // Forces and stable step of the initial state; the initial state goes
    // to the ParaView series
    model.evaluate();
    model.write(runTime.timeIndex() == 0);
    timeStep->check(model.stableDeltaT());
    timeStep->reportStart(Info, model.stableDeltaT(), model.stableStepLimit());
    if (!timeStep->withinMaxSteps(model.maxStepsStableDeltaT()))
    {
        timeStep->stopAtMaxSteps
        (
            model.maxStepsStableDeltaT(), model.stableStepLimit()
        );
    }

    Info<< "Starting time loop" << nl << endl;
    model.cost().startLoop();

    // Time::run() executes the function objects
    const auto run = [&runTime, &model]()
    {
        const costBreakdown::scope timed(model.cost(), costBreakdown::functions);
        return runTime.run();
    };
    while (run())
    {
        timeStep->setDeltaT(model.stableDeltaT());
        // The description is made only to stop: nothing is allocated in
        // the loop
        if (!timeStep->withinMaxSteps(model.maxStepsStableDeltaT()))
        {
            // The state is good, only too slow to go on: written to look at
            model.write(true);
            timeStep->stopAtMaxSteps
            (
                model.maxStepsStableDeltaT(), model.stableStepLimit(), true
            );
        }
        ++runTime;

        model.advance();
        model.evaluate();
        model.write();
        timeStep->reportWallEstimate(Info);

        if (timeStep->logTime())
        {
            Info<< "Time = " << runTime.timeName() << nl
                << "deltaT = " << runTime.deltaTValue()
                << ", Courant number = " << timeStep->courantNumber()
                << ", step " << runTime.timeIndex() << nl;
            model.report(Info);
            Info<< nl;
            timeStep->reportProgress(Info);
            model.cost().reportInterval(Info);
            Info<< "ExecutionTime = " << runTime.elapsedCpuTime()
                << " s  ClockTime = " << runTime.elapsedClockTime() << " s"
                << nl << endl;
        }
        {
            // Time's own record (uniform/time) at a write time
            const costBreakdown::scope timed
            (
                model.cost(), costBreakdown::output
            );
            runTime.write();
        }
    }

    model.cost().reportRun(Info);
    Info<< nl << "End\n" << endl;
    return 0;
}
