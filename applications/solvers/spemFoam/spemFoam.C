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
    constant/g, system/spemSchemes and system/controlDict:
        deltaT          first (adjustTimeStep yes) or fixed time step [s]
        adjustTimeStep  yes: deltaT = maxCo * stable step, bounded by
                        maxDeltaT; no: a deltaT above maxCo times the stable
                        step stops the run (default no)
        maxCo           Courant number: elements on the fastest wave speed
                        and the smallest element altitude, particles on
                        h/(c + |v|) (see sphFluid) (default 0.9; the
                        measured critical value is 1.33-1.64 for elements
                        on regular meshes, 1.5-1.75 for particles, see
                        tests/validation/stabilityTests.C and
                        sphValidationTests.C)
        maxDeltaT       upper bound on the adjusted step (default great)
        logInterval     steps between log entries (default 100; every write
                        time is logged too)
    Writes <time>/spem/ (restart state), VTK/<case>.pvd (ParaView series)
    and postProcessing/ (function objects of controlDict `functions`).

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "spemModel.H"

using namespace Foam;

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Explicit smoothed particle element method (SPEM) solver for"
        " fluid-structure interaction with free surfaces"
    );
    argList::noParallel();

    #include "setRootCase.H"
    #include "createTime.H"

    spemModel model(runTime);

    const dictionary& controls = runTime.controlDict();
    const bool adjustTimeStep =
        controls.getOrDefault<Switch>("adjustTimeStep", false);
    const scalar maxCo = controls.getOrDefault<scalar>("maxCo", 0.9);
    const scalar maxDeltaT = controls.getOrDefault<scalar>("maxDeltaT", GREAT);
    const label logInterval = controls.getOrDefault<label>("logInterval", 100);
    if (!(maxCo > 0) || logInterval < 1)
    {
        FatalIOErrorInFunction(controls)
            << "maxCo must be positive and logInterval at least 1"
            << exit(FatalIOError);
    }

    if (maxCo > 1)
    {
        WarningInFunction
            << "maxCo " << maxCo << " > 1: the explicit central-difference"
            << " scheme is unstable above Courant number 1" << nl << endl;
    }

    // Forces and stable step of the initial state; the initial state goes
    // to the ParaView series
    model.evaluate();
    model.write(runTime.timeIndex() == 0);

    //- Stop if a fixed time step exceeds the stable one
    auto checkFixedTimeStep = [&](const scalar stable)
    {
        if (runTime.deltaTValue() > maxCo*stable*(1 + 1e-12))
        {
            FatalIOErrorInFunction(controls)
                << "deltaT " << runTime.deltaTValue()
                << " exceeds the stable time step: Courant number "
                << runTime.deltaTValue()/stable << " > maxCo " << maxCo
                << " (stable deltaT at Courant number 1: " << stable << ")."
                << nl << "    Reduce deltaT below " << maxCo*stable
                << " or set adjustTimeStep yes." << exit(FatalIOError);
        }
    };
    if (!adjustTimeStep) checkFixedTimeStep(model.stableDeltaT());

    Info<< "Starting time loop" << nl << endl;

    // With writeControl adjustableRunTime the steps land on the write
    // times. OpenFOAM's own adjustment rounds the number of steps to the
    // next write time to the nearest integer, which can stretch a step by
    // up to 1.5 times: 6 % above maxCo was seen on the cylinder tutorials.
    // Here the count is rounded up, so no step exceeds maxCo.
    const bool landOnWriteTimes =
        Time::writeControlNames.getOrDefault
        (
            "writeControl", controls, Time::writeControls::wcTimeStep
        ) == Time::writeControls::wcAdjustableRunTime;
    const scalar writeInterval =
        landOnWriteTimes ? controls.get<scalar>("writeInterval") : GREAT;
    const scalar startTime = runTime.startTime().value();
    auto stepToWriteTime = [&](const scalar dt)
    {
        const scalar t = runTime.value() - startTime;
        const scalar tol = 1e-9*writeInterval;
        const scalar next =
            (std::floor((t + tol)/writeInterval) + 1)*writeInterval;
        const scalar toNext = next - t;
        const scalar n = std::ceil(toNext/dt*(1 - 1e-12));
        return toNext/std::max(n, scalar(1));
    };

    label step = 0;
    while (runTime.run())
    {
        const scalar stable = model.stableDeltaT();
        if (adjustTimeStep)
        {
            const scalar dt = min(maxCo*stable, maxDeltaT);
            if (landOnWriteTimes)
            {
                runTime.setDeltaT(stepToWriteTime(dt), false);
            }
            else
            {
                runTime.setDeltaT(dt);
            }
        }
        else
        {
            checkFixedTimeStep(stable);
        }

        ++runTime;
        ++step;

        model.advance();
        model.evaluate();
        model.write();

        if (step % logInterval == 0 || runTime.writeTime())
        {
            Info<< "Time = " << runTime.timeName() << nl
                << "deltaT = " << runTime.deltaTValue()
                << ", Courant number = " << runTime.deltaTValue()/stable
                << ", step " << runTime.timeIndex() << nl;
            model.report(Info);
            Info<< nl << "ExecutionTime = " << runTime.elapsedCpuTime()
                << " s  ClockTime = " << runTime.elapsedClockTime() << " s"
                << nl << endl;
        }
        runTime.write();
    }

    Info<< "End\n" << endl;
    return 0;
}
