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
#include "Time.H"
#include "spemModel.H"
#include "timeStepControl.H"

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
    timeStepControl::checkBeforeTime(args.path());
    #include "createTime.H"

    // controlDict first: a bad entry stops before the case is read
    timeStepControl timeStep(runTime);
    spemModel model(runTime);

    // Forces and stable step of the initial state; the initial state goes
    // to the ParaView series
    model.evaluate();
    model.write(runTime.timeIndex() == 0);
    timeStep.check(model.stableDeltaT());
    timeStep.reportStart(Info, model.stableDeltaT(), model.stableStepLimit());
    if (!timeStep.withinMaxSteps(model.stableDeltaT()))
    {
        timeStep.stopAtMaxSteps(model.stableDeltaT(), model.stableStepLimit());
    }

    Info<< "Starting time loop" << nl << endl;

    while (runTime.run())
    {
        timeStep.setDeltaT(model.stableDeltaT());
        // The description is made only to stop: nothing is allocated in
        // the loop
        if (!timeStep.withinMaxSteps(model.stableDeltaT()))
        {
            timeStep.stopAtMaxSteps
            (
                model.stableDeltaT(), model.stableStepLimit()
            );
        }
        ++runTime;

        model.advance();
        model.evaluate();
        model.write();
        timeStep.reportWallEstimate(Info);

        if (timeStep.logTime())
        {
            Info<< "Time = " << runTime.timeName() << nl
                << "deltaT = " << runTime.deltaTValue()
                << ", Courant number = " << timeStep.courantNumber()
                << ", step " << runTime.timeIndex() << nl;
            model.report(Info);
            Info<< nl;
            timeStep.reportProgress(Info);
            Info<< "ExecutionTime = " << runTime.elapsedCpuTime()
                << " s  ClockTime = " << runTime.elapsedClockTime() << " s"
                << nl << endl;
        }
        runTime.write();
    }

    Info<< "End\n" << endl;
    return 0;
}
