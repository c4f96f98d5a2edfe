#include "spemMethod.H"
#include "weaklyCompressibleNewtonian.H"
#include "wallParticles.H"
#include "sphKernel.H"
#include "elementToParticle.H"
#include "elementParticleCoupling.H"
#include "timeStepControl.H"
#include "parallelLoop.H"

#include <chrono>
#include <cmath>
#include <sstream>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(spemMethod, 0);
    defineRunTimeSelectionTable(spemMethod, dictionary);
}


// * * * * * * * * * * * * Protected Member Functions  * * * * * * * * * * * //

void Foam::spemMethod::collectCouplings()
{
    couplings_.clear();
    // Structure before bodies: the order of their particles in the step
    if (structureCoupling_) couplings_.push_back(structureCoupling_.get());
    if (bodyCoupling_) couplings_.push_back(bodyCoupling_.get());
}


void Foam::spemMethod::callHooks(void (spemCoupling::*hook)(couplingStep&))
{
    if (couplings_.empty()) return;
    const costBreakdown::scope timed(cost_, costBreakdown::couplings);
    couplingStep s
    {
        case_.mesh, case_.patchTypes, elements_.get(), particles_.get(),
        case_.bodies, lastDeltaT_, structure_
    };
    for (spemCoupling* c : couplings_) (c->*hook)(s);
}


void Foam::spemMethod::createElementHalf
(
    PtrList<spemMaterial>& materials,
    const std::vector<scalar>& density
)
{
    elements_.reset
    (
        new elementModel(case_.mesh, std::move(materials), density)
    );
    std::vector<elementModel::constraint> c;
    std::vector<scalar> normal, friction;
    // The viscosity of each triangle's fluid for the weak no-slip of fluid
    // elements (negative: a solid)
    const std::vector<label>& region = case_.mesh.triangleRegion();
    std::vector<scalar> viscosity(case_.mesh.nTriangles(), 0);
    for (label t = 0; t < case_.mesh.nTriangles(); ++t)
    {
        const label r = region[t];
        if (!elements_->hasMaterial(r)) continue;
        const spemMaterial& m = elements_->material(r);
        viscosity[t] = m.isFluid() ? m.rho()*m.kinematicViscosity() : -1;
    }
    nodeConstraints
    (
        case_.mesh, case_.patchTypes, case_.slipCornerAngle, c, normal,
        &viscosity, &friction, &case_.slidingNoSlip
    );
    elements_->setConstraints(std::move(c), std::move(normal));
    elements_->setWallFriction(std::move(friction));
    elements_->setGravity(case_.g[0], case_.g[1]);
    elements_->setMassDamping(case_.massDamping);
    elements_->setAbsorbingLayer(case_.absorbing);
    if (case_.restart.readElements(*elements_))
    {
        elements_->setPreviousDeltaT(case_.restart.readPreviousDeltaT());
        // The solids' last sub-step, if they sub-cycled (else it was the
        // step)
        const scalar subStep = case_.restart.readPreviousSubStep();
        if (subStep >= 0) elements_->setPreviousSubStep(subStep);
    }
    elements_->setSubCycleLoad(subCycling_.load());
}


void Foam::spemMethod::createParticleHalf
(
    particleSet&& ps,
    std::vector<scalar>&& rhoOld,
    const weaklyCompressibleNewtonian& fluid,
    const scalar spacing
)
{
    const dictionary& schemes = case_.schemes;
    const triMesh& mesh = case_.mesh;
    const sphFluid::controls ctrl = sphFluid::controls::read(schemes);

    // Walls: dummy particles at the mean spacing of the fluid particles,
    // enough layers to fill the kernel support
    const scalar h = ctrl.smoothingLengthRatio*spacing;
    const scalar kappa = sphKernel::New(schemes)->support();
    const label layers =
        ctrl.wallLayers > 0
      ? ctrl.wallLayers
      : label(std::ceil(kappa*ctrl.smoothingLengthRatio - 1e-9));
    const label nWall =
        appendWallParticles
        (
            mesh, case_.patchTypes, spacing, layers, fluid.rho(), h, ps
        );

    // No box: the tank decides which particles are lost (setTank below);
    // a particle flown away regardless stops the neighbour search
    const scalar boxMin[2] = {-GREAT, -GREAT}, boxMax[2] = {GREAT, GREAT};
    particles_.reset
    (
        new sphFluid
        (
            schemes, std::move(ps), fluid.rho(), fluid.c(),
            fluid.rho()*fluid.kinematicViscosity(), case_.g[0], case_.g[1],
            boxMin, boxMax
        )
    );
    particles_->setMassDamping(case_.massDamping);
    particles_->setAbsorbingLayer(case_.absorbing);
    particles_->timeSearchIn(&cost_);
    // A particle is outside the tank farther than a kernel support from it:
    // nearer, it still sees the wall particles
    particleTank_.reset
    (
        new tankBoundary
        (
            mesh, case_.patchTypes, kappa*particles_->particles().maxSmoothingLength()
        )
    );
    particles_->setTank(*particleTank_, case_.leaving);
    // The particles continue the elements' leapfrog (converted mid-run) or
    // the restart state's
    particles_->setPreviousDeltaT
    (
        elements_
      ? elements_->previousDeltaT()
      : case_.restart.readPreviousDeltaT()
    );
    createStructureCouplings(fluid.rho(), fluid.c(), spacing, layers, h);

    if (!rhoOld.empty())
    {
        // Restart: the fluid particles come first; walls start at rho0
        rhoOld.resize(particles_->particles().size(), fluid.rho());
        particles_->setOldDensity(rhoOld);
        std::vector<label> order;
        label stepsSinceSort = 0;
        if
        (
            case_.restart.readParticleOrder
            (
                particles_->particles(), order, stepsSinceSort
            )
        )
        {
            particles_->restoreOrder(order, stepsSinceSort);
        }
    }

    const sphFluid::controls& c = particles_->schemeControls();
    Info<< "Particle half: " << nWall << " wall particles in " << layers
        << " layers" << nl
        << "    spacing " << spacing << " m, h " << h << " m, kernel "
        << particles_->kernel().type() << nl
        << "    gradientCorrection "
        << sphFluid::gradientCorrectionTypeNames[c.gradientCorrection]
        << ", densityDiffusion " << c.densityDiffusion
        << ", shifting " << c.shifting
        << ", freeSurfaceThreshold " << c.freeSurfaceThreshold << nl;
}


void Foam::spemMethod::createStructureCouplings
(
    const scalar rho0,
    const scalar c,
    const scalar spacing,
    const label layers,
    const scalar h
)
{
    const triMesh& mesh = case_.mesh;

    // The rigid bodies seen by the particles
    if (!case_.bodies.empty())
    {
        bodyCoupling_.reset
        (
            new bodyParticleCoupling(case_.bodies, spacing, layers, rho0, h)
        );
        Info<< "    rigid bodies: " << bodyCoupling_->size()
            << " dummy particles" << nl;
        case_.restart.readAcceleration
        (
            "bodyParticle", bodyCoupling_->acceleration()
        );
    }

    // The solids seen by the particles (eq. 27)
    if (elements_)
    {
        structureCoupling_.reset
        (
            new structureParticleCoupling
            (
                mesh, *elements_, case_.patchTypes, spacing, layers, rho0, h
            )
        );
        if (structureCoupling_->size() == 0)
        {
            structureCoupling_.reset();
        }
        else
        {
            // The wall pressure's a_w without the step-to-step noise of
            // the lagged structure-fluid loop (wallAcceleration.H): over
            // ten times the time sound takes to cross h, i.e. at least ten
            // fluid steps (maxCo <= 1), also when the solids sub-cycle
            const scalar tau = 10*h/c;
            structureCoupling_->acceleration().setSmoothingTime(tau);
            Info<< "    structure-particle coupling: "
                << structureCoupling_->size()
                << " virtual particles in the solid regions, accelerations"
                << " smoothed over 10 h/c = " << tau << " s" << nl;
            case_.restart.readAcceleration
            (
                "virtualParticle", structureCoupling_->acceleration()
            );
        }
    }
    collectCouplings();
}


std::vector<bool> Foam::spemMethod::surveyFluidElements(scalar& maxArea)
{
    const triMesh& mesh = case_.mesh;
    const elementModel& em = *elements_;
    const label nTri = mesh.nTriangles();
    std::vector<bool> fluidTri(nTri, false);
    scalar areaSum = 0;
    label nFluid = 0;
    maxArea = 0;
    for (label t = 0; t < nTri; ++t)
    {
        const label r = mesh.triangleRegion()[t];
        if (!em.hasMaterial(r)) continue;   // void
        const spemMaterial& mat = em.material(r);
        if (!mat.isFluid()) continue;
        const auto* f = dynamic_cast<const weaklyCompressibleNewtonian*>(&mat);
        if (!f)
        {
            FatalErrorInFunction
                << "Fluid region " << mesh.regionNames()[r] << " ("
                << mat.type() << ") cannot become particles" << exit(FatalError);
        }
        if (!sameFluid(elementFluid_, *f))
        {
            FatalIOErrorInFunction(case_.properties)
                << "Fluid regions with different rho, c or mu: the particles"
                << " of method SPEM model one fluid" << exit(FatalIOError);
        }
        elementFluid_ = f;
        fluidTri[t] = true;
        const scalar A = mesh.triangleArea(t);
        areaSum += A;
        maxArea = max(maxArea, A);
        ++nFluid;
    }
    if (nFluid > 0) fluidSpacing_ = std::sqrt(areaSum/nFluid);
    return fluidTri;
}


Foam::scalar Foam::spemMethod::convertedSpacing() const
{
    return
        refinedRadiusRatio_ > 0
      ? refinedRadiusRatio_*fluidSpacing_
      : fluidSpacing_;
}


void Foam::spemMethod::convert(const std::vector<label>& triangles)
{
    const scalar ratio =
        sphFluid::controls::read(case_.schemes).smoothingLengthRatio;

    particleSet ps;
    refinementChange change;
    convertElements
    (
        case_.mesh, triangles, ratio, *elements_, ps, refinedRadiusRatio_,
        &change
    );
    convertedTriangles_.insert
    (
        convertedTriangles_.end(), triangles.begin(), triangles.end()
    );
    if (!particles_)
    {
        createParticleHalf
        (
            particleSet(), std::vector<scalar>(), *elementFluid_,
            convertedSpacing()
        );
    }
    particles_->appendFluid(ps);
    callHooks(&spemCoupling::afterConversion);

    Info<< "Conversion at time " << case_.runTime.timeName() << ": "
        << triangles.size() << " fluid elements became particles; "
        << elements_->nElements() << " elements, " << particles_->nFluid()
        << " particles";
    if (coupling())
    {
        Info<< ", " << coupling()->nInterfaceSegments()
            << " interface segments";
    }
    Info<< nl;
    if (refinedRadiusRatio_ > 0)
    {
        // A diagnostic: eq. (21) gives each refined particle its node's
        // velocity, which conserves linear momentum but not these two
        Info<< "    refinement (eqs. 19-22): " << ps.size()
            << " refined particles; eq. (21) changed, against one particle"
            << " per element, the angular momentum by "
            << change.angularMomentum << " kg m^2/s and the kinetic energy"
            << " by " << change.kineticEnergy << " J (of "
            << change.unsplitKineticEnergy << " J)" << nl;
    }
}


bool Foam::spemMethod::restartConversions()
{
    if (!case_.restart.readConvertedTriangles(convertedTriangles_))
    {
        return false;
    }
    if (convertedTriangles_.empty()) return true;
    elements_->removeTriangles(case_.mesh, convertedTriangles_);
    particleSet ps;
    std::vector<scalar> rhoOld;
    if (!case_.restart.readParticles(ps, rhoOld))
    {
        FatalErrorInFunction
            << "convertedTriangles in " << case_.runTime.timePath()/"spem"
            << " lists converted elements but there is no particle state"
            << exit(FatalError);
    }
    createParticleHalf
    (
        std::move(ps), std::move(rhoOld), *elementFluid_, convertedSpacing()
    );
    callHooks(&spemCoupling::afterConversion);
    return true;
}


void Foam::spemMethod::recordCheckpoint()
{
    checkpoint_.recorded = true;
    checkpoint_.nConverted = label(convertedTriangles_.size());
    checkpoint_.hadParticles = bool(particles_);
}


void Foam::spemMethod::undoEvaluation()
{
    const label nBefore = checkpoint_.nConverted;
    if (label(convertedTriangles_.size()) == nBefore) return;

    // The elements of the conversion back (the particle half's revert()
    // took its particles out); the element set of the last good state
    // builds its domains, masses and interfaces as they were
    const std::vector<label> undone
    (
        convertedTriangles_.begin() + nBefore, convertedTriangles_.end()
    );
    convertedTriangles_.resize(nBefore);
    elements_->restoreTriangles(case_.mesh, undone);
    if (!checkpoint_.hadParticles) removeParticleHalf();
    callHooks(&spemCoupling::afterConversion);

    Info<< "Conversion at time " << case_.runTime.timeName() << " undone"
        << " (the step failed): " << label(undone.size()) << " fluid elements"
        << " again; " << elements_->nElements() << " elements, "
        << (particles_ ? particles_->nFluid() : 0) << " particles" << nl;
}


void Foam::spemMethod::removeParticleHalf()
{
    structureCoupling_.reset();
    bodyCoupling_.reset();
    // The particles before the tank they refer to
    particles_.reset();
    particleTank_.reset();
    nOutsideToWarn_ = 0;
    collectCouplings();
}


void Foam::spemMethod::evaluateLastGood()
{
    if (elements_) elements_->evaluate();
    if (particles_) particles_->evaluate();
}


std::vector<Foam::label> Foam::spemMethod::trianglesInsideBodies() const
{
    std::vector<label> inside;
    const rigidBodies& bodies = case_.bodies;
    const triMesh& mesh = case_.mesh;
    if (bodies.empty()) return inside;
    const std::vector<scalar>& X = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    // The fluid regions (the one fluid model), from the dictionary: the
    // materials may already belong to the element model
    const dictionary& regions = case_.properties.subDict("regions");
    std::vector<bool> fluidRegion(mesh.nRegions(), false);
    forAll(mesh.regionNames(), r)
    {
        const dictionary* rd = regions.findDict(mesh.regionNames()[r]);
        fluidRegion[r] =
            rd && rd->get<word>("model") == "weaklyCompressibleNewtonian";
    }
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        if (!fluidRegion[mesh.triangleRegion()[t]]) continue;
        const label* n = &tri[3*t];
        const scalar cx = (X[2*n[0]] + X[2*n[1]] + X[2*n[2]])/3;
        const scalar cy = (X[2*n[0] + 1] + X[2*n[1] + 1] + X[2*n[2] + 1])/3;
        forAll(bodies, b)
        {
            if (bodies[b].contains(cx, cy))
            {
                inside.push_back(t);
                break;
            }
        }
    }
    return inside;
}


bool Foam::spemMethod::sameFluid
(
    const weaklyCompressibleNewtonian* first,
    const weaklyCompressibleNewtonian& other
)
{
    return
        !first
     || (
            first->rho() == other.rho() && first->c() == other.c()
         && first->kinematicViscosity() == other.kinematicViscosity()
        );
}


bool Foam::spemMethod::anySolid(const PtrList<spemMaterial>& materials)
{
    forAll(materials, r)
    {
        if (materials.set(r) && !materials[r].isFluid()) return true;
    }
    return false;
}


void Foam::spemMethod::ignoreInitialRelaxation() const
{
    // The relaxation moves particles, not elements: with fluid elements
    // the ghosts and the interface would have to move with it. Not an
    // error: a tutorial that needs it with method SPH keeps the entry
    // when a user switches it to SPEM
    const label iterations =
        sphFluid::controls::read(case_.schemes).initialRelaxation;
    if (iterations > 0)
    {
        IOWarningInFunction(case_.schemes)
            << "sph/initialRelaxation " << iterations << " relaxes the"
            << " particles of method SPH only; method "
            << case_.schemes.get<word>("method")
            << " starts from the elements' barycentres without it" << endl;
    }
}


void Foam::spemMethod::placeStructureParticles()
{
    structure_.clear();
    callHooks(&spemCoupling::beforeParticleEvaluate);
    if (structure_.size() > 0)
    {
        const costBreakdown::scope timed(cost_, costBreakdown::particles);
        particles_->setStructureParticles
        (
            structure_.size(), structure_.x.data(), structure_.v.data(),
            structure_.a.data(), structure_.m.data(), structure_.h.data()
        );
    }
}


void Foam::spemMethod::relaxInitialParticles()
{
    const label iterations =
        sphFluid::controls::read(case_.schemes).initialRelaxation;
    if (iterations <= 0 || !particles_) return;

    // The structures' and bodies' particles where the first step puts
    // them: the relaxation's grad C sees them as it sees the tank's walls
    placeStructureParticles();
    const scalar lastShift = particles_->relax(iterations);
    Info<< "    initial relaxation: " << iterations
        << " iterations, last shift at most " << lastShift
        << " smoothing lengths";
    if (structure_.size() > 0)
    {
        Info<< " (with " << structure_.size()
            << " particles of structures and bodies as walls)";
    }
    Info<< nl;
}


const char* const Foam::spemMethod::unstableHint =
    "Reduce maxCo or deltaT, or check the set-up near the failure.";


bool Foam::spemMethod::fail(const std::string& why, const std::string& hint)
{
    failure_ = why;
    failureHint_ = hint;
    return false;
}


bool Foam::spemMethod::checkBodiesInTank()
{
    const rigidBodies& bodies = case_.bodies;
    forAll(bodies, b)
    {
        const vector2D& c = bodies[b].position();
        if (!walls_->outside(c.x(), c.y()) || bodyReported_[b]) continue;
        std::ostringstream os;
        os  << "rigid body " << bodies[b].name() << " has left the tank: its"
            << " centre of mass (" << c.x() << ' ' << c.y() << ") is more"
            << " than " << walls_->reach() << " m outside it";
        if (case_.leaving == tankBoundary::leavingAction::warn)
        {
            WarningInFunction
                << "Time = " << case_.runTime.timeName() << ": "
                << os.str().c_str() << "; the run goes on (tank/leaving warn)"
                << endl;
            bodyReported_[b] = true;
            continue;
        }
        return fail
        (
            os.str(),
            "Check the body's motion and the tank's walls. tank/leaving warn"
            " in constant/spemProperties lets the run go on (a body cannot"
            " be removed)."
        );
    }
    return true;
}


void Foam::spemMethod::reportParticlesOutside()
{
    const sphFluid& p = *particles_;
    if (p.nRemovedLast() > 0)
    {
        Info<< "Time = " << case_.runTime.timeName() << ": removed "
            << p.nRemovedLast() << " fluid particles outside the tank, mass "
            << p.removedMassLast() << " kg/m (so far " << p.nRemoved()
            << " particles, " << p.removedMass() << " kg/m)" << nl;
    }
    if (p.nOutside() > nOutsideToWarn_)
    {
        WarningInFunction
            << "Time = " << case_.runTime.timeName() << ": " << p.nOutside()
            << " fluid particles are outside the tank by more than a kernel"
            << " support (" << particleTank_->reach() << " m); the run goes"
            << " on (tank/leaving warn)" << endl;
        nOutsideToWarn_ = 2*p.nOutside();
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemMethod::spemMethod(const spemCase& c)
:
    case_(c),
    elementFluid_(nullptr),
    fluidSpacing_(0),
    refinedRadiusRatio_(0),
    lastDeltaT_(0),
    particlesAdvanced_(false),
    nOutsideToWarn_(0),
    machToWarn_(0.1),
    evaluationsSinceMachCheck_(machCheckInterval - 1),
    subCycling_(c.runTime.controlDict()),
    lastSubSteps_(1)
{}


Foam::spemMethod::~spemMethod() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::spemMethod::setUpWalls()
{
    if (walls_) return;
    const triMesh& mesh = case_.mesh;
    // Two mean boundary segments: more than any node or body point moves
    // in a stable step, and a grid of a few cells per segment
    scalar length = 0;
    const std::vector<scalar>& X = mesh.points();
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        const label a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
        length += std::hypot(X[2*b] - X[2*a], X[2*b + 1] - X[2*a + 1]);
    }
    walls_.reset
    (
        new tankBoundary
        (
            mesh, case_.patchTypes, 2*length/max(label(1), mesh.nSegments())
        )
    );
    if (elements_) wallContact::releaseSolidSlipNodes(*elements_);
    contact_.reset(new wallContact(*walls_, elements_.get(), case_.bodies));
    bodyReported_.assign(case_.bodies.size(), false);
}


void Foam::spemMethod::restoreSubCyclingLoad()
{
    std::vector<scalar> load;
    if (elements_ && case_.restart.readSolidFluidLoad(load))
    {
        elements_->setFluidLoad(load);
    }
}


bool Foam::spemMethod::advanceElements(const scalar dt)
{
    const costBreakdown::scope timed(cost_, costBreakdown::elements);
    lastSubSteps_ = solidSubSteps(dt);
    if (lastSubSteps_ == 1)
    {
        if (!elements_->advance(dt))
        {
            return fail(elements_->failure(), unstableHint);
        }
        if (!contact_->correctStructures(*elements_, dt))
        {
            return fail(contact_->failure(), unstableHint);
        }
        return true;
    }

    // The fluid nodes by dt; the solid nodes in n sub-steps, the solid
    // elements' forces evaluated at each, the fluid's load (the fluid
    // elements' forces on the shared nodes, the particles' through the
    // virtual particles) that of the last evaluation, held
    if (!elements_->advanceFluidPartition(dt))
    {
        return fail(elements_->failure(), unstableHint);
    }
    // n sub-steps of dt/n; if an evaluation finds the solids' stable step
    // fallen below the sub-step (an element being crushed: hyperelastic
    // solids stiffen and shrink), the rest of the step is split again at
    // the new one, so that no sub-step outruns it. Above minParallelSolid
    // solid elements the sub-steps may run in one parallel region, if
    // that is faster here (solidTeam_): every thread runs this loop and
    // shares the passes of evaluateSolids and advanceSolidSubStep; rank 0
    // checks the step and corrects the contacts. The shared n, j, subDt,
    // splitAt and ok change only there, before a sync: every thread reads
    // the same values after it. The result is the same either way.
    const bool canTeam =
        maxThreads() > 1 && elements_->nSolidElements() > minParallelSolid;
    const bool teamed = canTeam && solidTeam_.chooseTeam();
    const auto start = std::chrono::steady_clock::now();
    label n = lastSubSteps_, j = 0;
    scalar subDt = dt/n, splitAt = 0;
    bool ok = true;
    threadTeam team;
    #pragma omp parallel if(teamed)
    for (label k = 0; ok && j < n; ++k)
    {
        const bool master = team.rank() == 0;
        if (k > 0)
        {
            const scalar elapsed = splitAt + j*subDt;
            const bool evaluated = elements_->evaluateSolids(elapsed, team);
            if (master)
            {
                ok =
                    evaluated
                  ? splitSubSteps(dt, elapsed, k, n, j, subDt, splitAt)
                  : fail(elements_->failure(), unstableHint);
            }
            team.sync();
            if (!ok) break;
        }
        const bool advanced = elements_->advanceSolidSubStep
        (
            subDt, splitAt + j*subDt, dt, team
        );
        if (master)
        {
            if (!advanced)
            {
                ok = fail(elements_->failure(), unstableHint);
            }
            else if (!contact_->correctStructures(*elements_, dt, k == 0))
            {
                ok = fail(contact_->failure(), unstableHint);
            }
            ++j;
        }
        team.sync();
    }
    if (canTeam)
    {
        solidTeam_.record
        (
            std::chrono::duration<scalar>
            (
                std::chrono::steady_clock::now() - start
            ).count(),
            lastSubSteps_
        );
    }
    return ok;
}


bool Foam::spemMethod::splitSubSteps
(
    const scalar dt,
    const scalar elapsed,
    const label k,
    label& n,
    label& j,
    scalar& subDt,
    scalar& splitAt
)
{
    const scalar solid = elements_->solidStableDeltaT();
    if (subDt <= subCycling_.maxCo()*solid*(1 + 1e-12)) return true;
    const label more = subCycling_.subSteps(dt - elapsed, solid);
    if (more > subCycling_.maxSteps())
    {
        std::ostringstream os;
        os  << "the solids' stable step fell to " << solid
            << " s within a sub-cycled step, set by ";
        describeElementLimit(os, elements_->solidStableLimit());
        os  << "; the step would take " << more << " more"
            << " sub-steps (maxSteps " << subCycling_.maxSteps()
            << "): an element is crushed";
        return fail
        (
            os.str(),
            "A material too soft for the load, or a blow-up in"
            " slow motion; check the solid near the failure."
        );
    }
    splitAt = elapsed;
    subDt = (dt - elapsed)/more;
    n = more;
    j = 0;
    lastSubSteps_ = k + more;
    return true;
}


bool Foam::spemMethod::advance(const scalar dt)
{
    // The last evaluation succeeded: nothing of it is undone any more
    checkpoint_.recorded = false;
    particlesAdvanced_ = false;
    callHooks(&spemCoupling::beforeElementAdvance);
    if (elements_ && !advanceElements(dt)) return false;
    callHooks(&spemCoupling::afterElementAdvance);
    particlesAdvanced_ = bool(particles_);
    if (particles_)
    {
        const costBreakdown::scope timed(cost_, costBreakdown::particles);
        if (!particles_->advance(dt))
        {
            return fail(particles_->failure(), unstableHint);
        }
    }
    // The bodies under the fluid's force of the last evaluation, from
    // t^n = t^{n+1} - dt (the Time is already at the new time)
    rigidBodies& bodies = case_.bodies;
    if (!bodies.empty() && !advanceBodies(dt)) return false;
    callHooks(&spemCoupling::afterBodyAdvance);
    lastDeltaT_ = dt;
    return true;
}


bool Foam::spemMethod::advanceBodies(const scalar dt)
{
    const costBreakdown::scope timed(cost_, costBreakdown::bodies);
    rigidBodies& bodies = case_.bodies;
    forAll(bodies, b)
    {
        scalar F[2], M;
        bodyLoad(b, F, M);
        bodies[b].advance
        (
            case_.runTime.value() - dt, dt, F[0], F[1], M,
            case_.g[0], case_.g[1]
        );
    }
    if (!contact_->correctBodies(bodies, dt))
    {
        return fail
        (
            contact_->failure(),
            "Reduce maxCo or deltaT if the body moved too far in one"
            " step; a prescribed motion into a wall must be changed in"
            " constant/rigidBodyProperties."
        );
    }
    return checkBodiesInTank();
}


bool Foam::spemMethod::evaluate()
{
    callHooks(&spemCoupling::beforeElementEvaluate);
    if (elements_)
    {
        const costBreakdown::scope timed(cost_, costBreakdown::elements);
        if (!elements_->evaluate())
        {
            return fail(elements_->failure(), unstableHint);
        }
    }
    if (!particles_)
    {
        checkFlowMach();
        return true;
    }

    placeStructureParticles();
    const costBreakdown::scope timed(cost_, costBreakdown::particles);
    if (!particles_->evaluate())
    {
        // A particle that leaves faster than sound was thrown out by a
        // blow-up, not carried out by the flow
        const fastestFluid f = findFastestFluid();
        std::string hint = unstableHint;
        if (particles_->failedLeavingTank() && f.mach < 1)
        {
            hint =
                "Particles leave the tank: if the flow splashes out, close"
                " it with walls where they cross, or set tank/leaving to"
                " remove (their mass is logged) or warn in"
                " constant/spemProperties; if they were thrown out (a"
                " blow-up: maxCo above 1, or a jump in the log's forces),"
                " reduce maxCo or deltaT.";
        }
        else if (f.mach >= 1)
        {
            std::ostringstream os;
            os  << "The fastest fluid particle moves at " << f.speed
                << " m/s, above the sound speed c " << f.c << " m/s: the"
                " step blew up. " << unstableHint;
            hint = os.str();
        }
        return fail(particles_->failure(), hint);
    }
    reportParticlesOutside();
    checkFlowMach();

    // The particles' forces on the elements are the external forces of
    // this evaluation: eq. (25) on the fluid elements' interface, eq. (27)
    // on the solids
    if (elements_) elements_->clearExternalForce();
    callHooks(&spemCoupling::afterParticleEvaluate);
    return true;
}


void Foam::spemMethod::revertToLastGood()
{
    // Each half's state before the last advance() (the particle half
    // without the particles appended since; the elements always advance
    // first), then what the failed evaluation changed besides the state
    if (elements_) elements_->revert();
    if (particles_ && particlesAdvanced_) particles_->revert();
    particlesAdvanced_ = false;
    if (checkpoint_.recorded) undoEvaluation();
    checkpoint_.recorded = false;
    // Stresses and pressures of the good state for the output (it
    // evaluated before)
    evaluateLastGood();
}


void Foam::spemMethod::describeElementLimit
(
    std::ostream& os,
    const stepLimit& l
) const
{
    const spemMaterial& mat = elements_->material(l.region);
    os  << "the " << stepLimit::name(l.which) << " limit of the elements"
        << " of region " << elements_->regions()[l.region].name << ": ";
    switch (l.which)
    {
        case stepLimit::criterion::acoustic:
            os  << "h/c with c " << mat.waveSpeed() << " m/s (entry c)";
            if (mat.bulkViscosity() > 0)
            {
                os  << " and h an altitude times sqrt(1 + xi^2) - xi,"
                    << " xi = " << mat.bulkViscosity() << " sqrt(A)/h"
                    << " (entry bulkViscosity)";
            }
            break;
        case stepLimit::criterion::viscous:
            os  << "0.25 h^2 rho/mu with mu "
                << mat.rho()*mat.kinematicViscosity() << " Pa s, rho "
                << mat.rho() << " kg/m3 (entries mu, rho)";
            break;
        default:
            os  << "h/c_p with the longitudinal wave speed c_p "
                << mat.waveSpeed() << " m/s at rest (entries E, nu, rho)";
            break;
    }
    if (l.length > 0) os << ", smallest altitude h " << l.length << " m";
}


std::string Foam::spemMethod::stableStepLimit() const
{
    std::ostringstream os;
    // With the solids sub-cycling the step is the fluid's
    const bool sub = subCycles();
    const stepLimit* elementLimit =
        !elements_ ? nullptr
      : sub ? &elements_->fluidStableLimit() : &elements_->stableLimit();
    const bool fromElements =
        elements_
     && (
            !particles_
         || (sub ? elements_->fluidStableDeltaT() : elements_->stableDeltaT())
         <= particles_->stableDeltaT()
        );
    if (fromElements && elementLimit->region >= 0)
    {
        describeElementLimit(os, *elementLimit);
    }
    else if (particles_ && particles_->stableLimit().which != stepLimit::criterion::none)
    {
        const sphFluid& p = *particles_;
        const stepLimit& l = p.stableLimit();
        os  << "the " << stepLimit::name(l.which) << " limit of the fluid"
            << " particles: ";
        switch (l.which)
        {
            case stepLimit::criterion::acoustic:
                os  << "h/(c + |v|) with c " << p.c() << " m/s (entry c)";
                break;
            case stepLimit::criterion::viscous:
                os  << "0.125 h^2 rho/mu with mu " << p.mu() << " Pa s, rho "
                    << p.rho0() << " kg/m3 (entries mu, rho)";
                break;
            default:
                os  << "0.25 sqrt(h/|a|), the largest acceleration |a| of a"
                    << " particle, with gravity (" << p.gx() << ' ' << p.gy()
                    << ") m/s2 (constant/g)";
                break;
        }
    }
    else
    {
        os  << "no limit (no elements or particles)";
    }

    // What the solids do
    if (sub)
    {
        const scalar solid = elements_->solidStableDeltaT();
        os  << "\n    solids sub-cycle (subCycling on, load "
            << subCycling_.loadName()
            << "): ceil(deltaT/(Co_s dt_s)) sub-steps per step at Co_s "
            << subCycling_.maxCo() << " (subCyclingMaxCo), "
            << subCycling_.subSteps(subCycling_.stepMaxCo()*stableDeltaT(), solid)
            << " at maxCo times the stable step; the solids' stable step dt_s "
            << solid << " s is set by ";
        describeElementLimit(os, elements_->solidStableLimit());
    }
    else if
    (
        elements_ && elements_->nSolidNodes() > 0
     && fluidStableDeltaT() < GREAT
    )
    {
        os  << "\n    solids: no sub-cycling ("
            << (
                   subCycling_.enabled()
                 ? "their stable step is more than half the fluid's"
                 : "subCycling off"
               )
            << ")";
    }
    return os.str();
}


Foam::scalar Foam::spemMethod::fluidStableDeltaT() const
{
    scalar dt = GREAT;
    if (elements_) dt = min(dt, elements_->fluidStableDeltaT());
    if (particles_) dt = min(dt, particles_->stableDeltaT());
    return dt;
}


bool Foam::spemMethod::subCycles() const
{
    return
        elements_ && elements_->nSolidNodes() > 0
     && subCycling_.active(fluidStableDeltaT(), elements_->solidStableDeltaT());
}


Foam::label Foam::spemMethod::solidSubSteps(const scalar dt) const
{
    return
        subCycles()
      ? subCycling_.subSteps(dt, elements_->solidStableDeltaT())
      : 1;
}


Foam::scalar Foam::spemMethod::maxStepsStableDeltaT() const
{
    const scalar dt = stableDeltaT();
    if (!subCycles()) return dt;
    // Sub-steps of Co_s dt_s counted as steps of maxCo times this
    return min
    (
        dt,
        subCycling_.maxCo()/subCycling_.stepMaxCo()
       *elements_->solidStableDeltaT()
    );
}


Foam::scalar Foam::spemMethod::stableDeltaT() const
{
    if (subCycles()) return fluidStableDeltaT();
    scalar dt = GREAT;
    if (elements_) dt = min(dt, elements_->stableDeltaT());
    if (particles_) dt = min(dt, particles_->stableDeltaT());
    return dt;
}


void Foam::spemMethod::bodyLoad(const label b, scalar F[2], scalar& M) const
{
    F[0] = F[1] = M = 0;
    for (const spemCoupling* c : couplings_) c->addBodyLoad(b, F, M);
}


Foam::restartState::content Foam::spemMethod::state() const
{
    restartState::content c;
    c.elements = elements_.get();
    c.particles = particles_.get();
    c.bodies = &case_.bodies;
    c.convertedTriangles = &convertedTriangles_;
    if (structureCoupling_)
    {
        c.virtualParticles = &structureCoupling_->acceleration();
    }
    if (bodyCoupling_) c.bodyParticles = &bodyCoupling_->acceleration();
    c.previousDeltaT =
        elements_
      ? elements_->previousDeltaT()
      : particles_ ? particles_->previousDeltaT() : -1;
    // The solids' last sub-step (bit-identical restarts), if they
    // sub-cycled in the last step: otherwise it is previousDeltaT and the
    // state is the one written without sub-cycling
    if
    (
        elements_ && elements_->nSolidNodes() > 0
     && elements_->previousSubStep() != elements_->previousDeltaT()
    )
    {
        c.previousSubStep = elements_->previousSubStep();
        solidFluidLoad_ = elements_->fluidLoad();
        c.solidFluidLoad = &solidFluidLoad_;
    }
    return c;
}


Foam::spemMethod::fastestFluid Foam::spemMethod::findFastestFluid() const
{
    // Compared by the squares, (|v|/c)^2, one square root at the end: the
    // search visits every fluid particle and every fluid element's nodes
    fastestFluid f;
    scalar mach2 = 0, speed2 = 0;
    const auto keepFaster =
        [&]
        (
            const scalar vx,
            const scalar vy,
            const scalar c,
            const scalar x,
            const scalar y,
            const bool particle
        )
        {
            const scalar v2 = vx*vx + vy*vy;
            if (v2 > mach2*c*c)
            {
                mach2 = v2/(c*c);
                speed2 = v2;
                f = {0, 0, c, x, y, particle};
            }
        };
    if (particles_)
    {
        const sphFluid& p = *particles_;
        const std::vector<scalar>& v = p.particles().velocities();
        const std::vector<scalar>& x = p.particles().positions();
        const std::vector<particleSet::kind>& kind = p.particles().kinds();
        const scalar c = p.c();
        for (label i = 0; i < label(kind.size()); ++i)
        {
            if (kind[i] != particleSet::kind::fluid) continue;
            keepFaster(v[2*i], v[2*i + 1], c, x[2*i], x[2*i + 1], true);
        }
    }
    if (elements_)
    {
        const elementModel& em = *elements_;
        const std::vector<scalar>& v = em.velocities();
        const std::vector<scalar>& x = em.positions();
        const std::vector<label>& nodes = em.elementNodes();
        forAll(em.regions(), ri)
        {
            const elementModel::region& r = em.regions()[ri];
            if (r.elemBegin == r.elemEnd) continue;
            if (!em.hasMaterial(ri) || !em.material(ri).isFluid()) continue;
            const scalar c = em.material(ri).waveSpeed();
            for (label e = r.elemBegin; e < r.elemEnd; ++e)
            {
                for (label k = 0; k < 3; ++k)
                {
                    const label n = nodes[3*e + k];
                    keepFaster
                    (
                        v[2*n], v[2*n + 1], c, x[2*n], x[2*n + 1], false
                    );
                }
            }
        }
    }
    f.mach = std::sqrt(mach2);
    f.speed = std::sqrt(speed2);
    return f;
}


void Foam::spemMethod::checkFlowMach()
{
    // Every machCheckInterval evaluations: the fastest speed changes over
    // many steps, and the search visits every fluid particle and node
    if (machToWarn_ > 1 || ++evaluationsSinceMachCheck_ < machCheckInterval)
    {
        return;
    }
    evaluationsSinceMachCheck_ = 0;
    const fastestFluid f = findFastestFluid();
    if (f.mach <= machToWarn_) return;
    WarningInFunction
        << "Time = " << case_.runTime.timeName() << ": the flow reaches Mach "
        << f.mach << ": a fluid " << (f.particle ? "particle" : "element node")
        << " at (" << f.x << ' ' << f.y << ") moves at " << f.speed
        << " m/s, above c/" << (machToWarn_ < 0.2 ? "10" : "3") << " (c "
        << f.c << " m/s). The weakly compressible model's density errors"
        << " grow as Ma^2 (" << 100*f.mach*f.mach << " % here): raise c"
        << " (entry c of the fluid region) to about 10 times the fastest"
        << " flow speed." << endl;
    machToWarn_ = machToWarn_ < 0.2 ? 1.0/3 : 2;
}


void Foam::spemMethod::report(Ostream& os) const
{
    os  << "elements = " << (elements_ ? elements_->nElements() : 0)
        << ", nodes = " << (elements_ ? elements_->nNodes() : 0)
        << ", particles = " << (particles_ ? particles_->nFluid() : 0);
    if (particles_)
    {
        const scalar* f = particles_->wallForce();
        os  << ", wall particles = " << particles_->nWall()
            << ", force on walls = (" << f[0] << ' ' << f[1] << ')';
    }
    reportInterface(os);
    if (lastSubSteps_ > 1)
    {
        os  << ", solid sub-steps = " << lastSubSteps_;
        const scalar team = solidTeam_.cost(true);
        const scalar one = solidTeam_.cost(false);
        if (team >= 0 && one >= 0)
        {
            // Which of the two runs them now, by its mean time a sub-step
            const auto us = [](const scalar c) { return std::round(1e7*c)/10; };
            os  << " (" << (solidTeam_.teamFaster() ? "on " : "not on ")
                << maxThreads() << " threads: " << us(team)
                << " us a sub-step, on one " << us(one) << " us)";
        }
    }
    if (structureCoupling_)
    {
        const scalar* f = structureCoupling_->force();
        os  << ", force on solids = (" << f[0] << ' ' << f[1] << ')';
    }
    forAll(case_.bodies, b)
    {
        const rigidBody& body = case_.bodies[b];
        scalar f[2], m;
        bodyLoad(b, f, m);
        os  << ", body " << body.name() << " at (" << body.position().x()
            << ' ' << body.position().y() << ") velocity ("
            << body.velocity().x() << ' ' << body.velocity().y()
            << ") force (" << f[0] << ' ' << f[1] << ')';
    }
}


// ************************************************************************* //
