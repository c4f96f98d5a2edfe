#include "spemModel.H"
#include "Time.H"
#include "uniformDimensionedFields.H"
#include "checkKeywords.H"
#include "saneRanges.H"
#include "IFstream.H"
#include "sphFluid.H"
#include "vtkModelWriter.H"

#include <sstream>
#include <utility>

namespace Foam
{
    defineTypeNameAndDebug(spemModel, 0);
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::PtrList<Foam::spemMaterial> Foam::spemModel::readMaterials() const
{
    const dictionary& regionsDict = subDict("regions");

    // Every entry must name a mesh region (catches misspelt zone names)
    for (const entry& e : regionsDict)
    {
        if (mesh_.findRegion(e.keyword()) < 0)
        {
            FatalIOErrorInFunction(regionsDict)
                << "Region '" << e.keyword() << "' is not a region of the"
                << " mesh. Mesh regions (cellZones): " << mesh_.regionNames()
                << exit(FatalIOError);
        }
    }

    PtrList<spemMaterial> materials(mesh_.nRegions());
    forAll(mesh_.regionNames(), r)
    {
        const word& name = mesh_.regionNames()[r];
        if (!regionsDict.isDict(name))
        {
            FatalIOErrorInFunction(regionsDict)
                << "Missing sub-dictionary 'regions/" << name
                << "': every mesh region needs a material"
                << exit(FatalIOError);
        }
        const dictionary& d = regionsDict.subDict(name);
        if (d.getOrDefault<word>("model", word::null) == "void")
        {
            checkKeywords(d, {"model"});
            continue;
        }
        materials.set(r, spemMaterial::New(name, d));
    }
    return materials;
}


void Foam::spemModel::readBoundaries()
{
    const dictionary& bcDict = subDict("boundaries");
    for (const entry& e : bcDict)
    {
        if (mesh_.findPatch(e.keyword()) < 0)
        {
            FatalIOErrorInFunction(bcDict)
                << "Patch '" << e.keyword() << "' is not a patch of the mesh."
                << " Mesh patches: " << mesh_.patchNames()
                << exit(FatalIOError);
        }
    }

    patchTypes_.setSize(mesh_.nPatches());
    slidingNoSlip_.setSize(mesh_.nPatches(), false);
    forAll(mesh_.patchNames(), p)
    {
        const word& name = mesh_.patchNames()[p];
        if (!bcDict.isDict(name))
        {
            FatalIOErrorInFunction(bcDict)
                << "Missing sub-dictionary 'boundaries/" << name
                << "': every mesh patch needs a condition, one of "
                << patchTypeNames << exit(FatalIOError);
        }
        const dictionary& d = bcDict.subDict(name);
        checkKeywords(d, {"type", "fluidElements"});
        patchTypes_[p] = getCheckedEnum(d, "type", patchTypeNames);
        // How the nodes of fluid elements meet a no-slip wall (see
        // patchConditions): pinned (default) or slide with the wall shear
        const word fluidElements =
            d.getOrDefault<word>("fluidElements", "pinned");
        if
        (
            (fluidElements != "pinned" && fluidElements != "slide")
         || (fluidElements == "slide" && patchTypes_[p] != patchType::noSlipWall)
        )
        {
            FatalIOErrorInFunction(d)
                << "boundaries/" << name << "/fluidElements: 'pinned' or"
                << " 'slide' on a noSlipWall patch, found '" << fluidElements
                << "' on a " << patchTypeNames[patchTypes_[p]] << " patch"
                << exit(FatalIOError);
        }
        slidingNoSlip_[p] = fluidElements == "slide";
    }
}


void Foam::spemModel::readGravity()
{
    IOobject gIO
    (
        "g",
        runTime_.constant(),
        runTime_,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    g_[0] = 0;
    g_[1] = 0;
    if (!gIO.typeHeaderOk<uniformDimensionedVectorField>(true))
    {
        Info<< "No constant/g: no gravity" << nl;
        return;
    }
    // The value checked before anything squares it (1e200 overflowed in
    // |g| and stopped with SIGFPE)
    {
        IFstream is(gIO.objectPath());
        getCheckedVector(dictionary(is), "value", saneRange::gravity);
    }
    const uniformDimensionedVectorField g(gIO);
    if (mag(g.value().z()) > SMALL*mag(g.value()))
    {
        FatalErrorInFunction
            << "Gravity in " << gIO.objectPath() << " must lie in the x-y"
            << " plane of the 2D mesh, found " << g.value()
            << exit(FatalError);
    }
    g_[0] = g.value().x();
    g_[1] = g.value().y();
}


void Foam::spemModel::checkMachNumber
(
    const PtrList<spemMaterial>& materials
) const
{
    const scalar gMag = std::sqrt(g_[0]*g_[0] + g_[1]*g_[1]);
    if (!(gMag > 0)) return;
    // The height of the mesh along g
    const std::vector<scalar>& x = mesh_.points();
    scalar lo = GREAT, hi = -GREAT;
    for (label i = 0; i < mesh_.nPoints(); ++i)
    {
        const scalar s = (x[2*i]*g_[0] + x[2*i + 1]*g_[1])/gMag;
        lo = min(lo, s);
        hi = max(hi, s);
    }
    const scalar H = hi - lo;
    const scalar freeFall = std::sqrt(2*gMag*H);
    const dictionary& regionsDict = subDict("regions");
    forAll(materials, r)
    {
        if (!materials.set(r) || !materials[r].isFluid()) continue;
        const scalar c = materials[r].waveSpeed();
        if (c > freeFall) continue;
        FatalIOErrorInFunction(regionsDict.subDict(materials[r].name()))
            << "Entry 'c' of region " << materials[r].name() << ": c " << c
            << " m/s is not above the speed of a free fall over the height"
            << " of the mesh, sqrt(2 |g| H) = " << freeFall << " m/s (|g| "
            << gMag << " m/s2 of constant/g, H " << H << " m)." << nl
            << "    The fluid would flow at Mach > 1, outside the weakly"
            << " compressible model: c is usually 10 x the largest flow"
            << " speed." << exit(FatalIOError);
    }
}


Foam::restartState::bounds Foam::spemModel::restartBounds
(
    const PtrList<spemMaterial>& materials
) const
{
    restartState::bounds b;
    // A box no particle of a valid state reaches: the mesh enlarged by
    // 1000 times its size on every side (the tank decides which particles
    // are lost, and beyond an open patch it has no end; this only catches
    // a corrupt number)
    const scalar lost = 1000;
    const std::vector<scalar>& x = mesh_.points();
    for (int k = 0; k < 2; ++k)
    {
        scalar lo = GREAT, hi = -GREAT;
        for (label i = 0; i < mesh_.nPoints(); ++i)
        {
            lo = min(lo, x[2*i + k]);
            hi = max(hi, x[2*i + k]);
        }
        b.boxMin[k] = lo - lost*(hi - lo);
        b.boxMax[k] = hi + lost*(hi - lo);
    }
    b.maxSpeed = 0;
    forAll(materials, r)
    {
        if (!materials.set(r)) continue;
        b.maxSpeed = max(b.maxSpeed, materials[r].waveSpeed());
        if (materials[r].isFluid()) b.rho0 = materials[r].rho();
    }
    return b;
}


Foam::scalar Foam::spemModel::readDamping() const
{
    const dictionary* dampingDict = findDict("damping");
    if (!dampingDict) return 0;
    checkKeywords(*dampingDict, {"massProportional", "absorbingLayer"});
    return getCheckedOrDefault
    (
        *dampingDict, "massProportional", 0, saneRange::damping
    );
}


Foam::absorbingLayer Foam::spemModel::readAbsorbingLayer() const
{
    const dictionary* dampingDict = findDict("damping");
    return dampingDict ? absorbingLayer::read(*dampingDict) : absorbingLayer();
}


Foam::tankBoundary::leavingAction Foam::spemModel::readLeaving() const
{
    const dictionary* tankDict = findDict("tank");
    if (!tankDict) return tankBoundary::leavingAction::stop;
    checkKeywords(*tankDict, {"leaving"});
    return getCheckedEnum
    (
        *tankDict, "leaving", tankBoundary::leavingActionNames,
        tankBoundary::leavingAction::stop
    );
}


void Foam::spemModel::checkBodiesAtStart() const
{
    if (bodies_.empty()) return;
    const tankBoundary& tank = method_->walls();
    // Touching is allowed (a body resting on the floor): overlaps below
    // round-off of the coordinates are not overlaps
    const scalar touching = 1e-9*tank.size();
    const scalar spacing = 0.5*tank.reach();

    auto stop = [&](const label b, const std::string& why)
    {
        const IOdictionary dict
        (
            IOobject
            (
                rigidBodies::dictName, runTime_.constant(), runTime_,
                IOobject::MUST_READ, IOobject::NO_WRITE, false
            )
        );
        FatalIOErrorInFunction(dict.subDict("bodies").subDict(bodies_[b].name()))
            << "Rigid body '" << bodies_[b].name() << "' (entry bodies/"
            << bodies_[b].name() << "): " << why.c_str()
            << exit(FatalIOError);
    };

    tankBoundary::nearestPoint q;
    forAll(bodies_, b)
    {
        const rigidBody& body = bodies_[b];
        const vector2D& c = body.position();
        if (tank.outside(c.x(), c.y()))
        {
            std::ostringstream os;
            os  << "its centre of mass (" << c.x() << ' ' << c.y()
                << ") is outside the tank (the mesh inside its wall"
                << " patches): move it into the mesh";
            stop(b, os.str());
        }
        const std::vector<scalar> P = body.surfacePoints(spacing);
        for (label i = 0; i < label(P.size()/2); ++i)
        {
            if
            (
                tank.behindWall(P[2*i], P[2*i + 1], q)
             && q.signedDistance > touching
            )
            {
                std::ostringstream os;
                os  << "it overlaps a wall: its surface point (" << P[2*i]
                    << ' ' << P[2*i + 1] << ") is " << q.signedDistance
                    << " m behind the wall at (" << q.x << ' ' << q.y
                    << "). Move it into the tank (touching a wall is"
                    << " allowed)";
                stop(b, os.str());
            }
        }
        // A corner of the tank inside the body
        for (label e = 0; e < tank.nEdges(); ++e)
        {
            if (!tank.isWall(e)) continue;
            const label n = tank.edgeNodes()[2*e];
            const scalar x = tank.points()[2*n], y = tank.points()[2*n + 1];
            if (body.signedDistance(x, y) < -touching)
            {
                std::ostringstream os;
                os  << "it overlaps a wall: the wall point (" << x << ' '
                    << y << ") is inside it. Move it into the tank";
                stop(b, os.str());
            }
        }
        for (label other = 0; other < b; ++other)
        {
            for (label i = 0; i < label(P.size()/2); ++i)
            {
                if (bodies_[other].signedDistance(P[2*i], P[2*i + 1]) < -touching)
                {
                    std::ostringstream os;
                    os  << "it overlaps rigid body '" << bodies_[other].name()
                        << "': its surface point (" << P[2*i] << ' '
                        << P[2*i + 1] << ") is inside it. Bodies may touch"
                        << " but not overlap";
                    stop(b, os.str());
                }
            }
        }
    }
}


void Foam::spemModel::describe() const
{
    forAll(bodies_, b)
    {
        Info<< "    rigid body " << bodies_[b].name() << ": "
            << bodies_[b].shape().type() << ", "
            << bodies_[b].motion().type() << nl;
    }
    Info<< "Mesh: " << mesh_.nPoints() << " nodes, " << mesh_.nTriangles()
        << " triangles, " << mesh_.nSegments() << " boundary segments" << nl;
    if (const elementModel* em = method_->elements())
    {
        for (const elementModel::region& r : em->regions())
        {
            const label ri = &r - em->regions().cdata();
            Info<< "    region " << r.name << ": "
                << (em->hasMaterial(ri) ? em->material(ri).type() : word("void"))
                << ", "
                << r.elemEnd - r.elemBegin << " elements, "
                << r.domainEnd - r.domainBegin << " smoothing domains" << nl;
        }
    }
    forAll(mesh_.patchNames(), p)
    {
        Info<< "    patch " << mesh_.patchNames()[p] << ": "
            << patchTypeNames[patchTypes_[p]] << nl;
    }
    if (case_->massDamping > 0)
    {
        Info<< "    mass-proportional damping " << case_->massDamping
            << " 1/s" << nl;
    }
    if (case_->absorbing.active())
    {
        Info<< "    ";
        case_->absorbing.describe(Info);
        Info<< nl;
    }
    Info<< endl;
}


void Foam::spemModel::stopWithLastGoodState
(
    const std::string& failure,
    const std::string& hint
)
{
    // A copy: re-evaluating the good state below clears the failure
    // message of the half that failed
    const std::string why = failure;
    const scalar tFail = runTime_.value();

    // A failure before the first step is the start state's: the input
    const bool atStart = runTime_.timeIndex() == runTime_.startTimeIndex();
    const std::string what =
        atStart
      ? "The state at the start time " + std::string(runTime_.timeName())
      + " is not valid: check the case's input (mesh, dictionaries, and the"
        " restart files of that time). " + hint
      : hint;

    // The failed state is the current one; the previous one is good
    if (!atStart)
    {
        method_->revertToLastGood();
        runTime_.setTime
        (
            tFail - runTime_.deltaTValue(), runTime_.timeIndex() - 1
        );
    }
    write(true);
    FatalErrorInFunction
        << "Run stopped at time " << tFail << ": " << why.c_str() << nl
        << "    The last good state (time " << runTime_.timeName()
        << ") has been written to " << runTime_.timePath()
        << " and VTK/." << nl
        << "    " << what.c_str() << exit(FatalError);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemModel::spemModel(Time& runTime)
:
    IOdictionary
    (
        IOobject
        (
            "spemProperties",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    runTime_(runTime),
    schemes_
    (
        IOobject
        (
            "spemSchemes",
            runTime.system(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    ),
    mesh_(triMesh::read(runTime)),
    bodies_(runTime),
    restart_(runTime),
    // controlDict vtkFormat and vtkFields checked before the case is read
    vtk_(new vtkModelWriter(runTime)),
    lastWrittenTime_(-GREAT)
{
    checkKeywords
    (
        *this,
        {"regions", "boundaries", "damping", "slipCornerAngle", "tank"}
    );
    checkKeywords
    (
        schemes_, {"method", "kernel", "sph", "conversion", "coupling"}
    );

    PtrList<spemMaterial> materials = readMaterials();
    bool anyMaterial = false;
    forAll(materials, r) anyMaterial = anyMaterial || materials.set(r);
    if (!anyMaterial)
    {
        FatalIOErrorInFunction(subDict("regions"))
            << "Every region is void (empty space): nothing to solve"
            << exit(FatalIOError);
    }
    const scalar damping = readDamping();
    readBoundaries();
    readGravity();
    checkMachNumber(materials);
    restart_.setBounds(restartBounds(materials));

    case_.reset
    (
        new spemCase
        {
            runTime_, schemes_, *this, mesh_, bodies_, patchTypes_, g_,
            damping, readAbsorbingLayer(),
            getOrDefault<scalar>("slipCornerAngle", 10), restart_,
            readLeaving(), slidingNoSlip_
        }
    );
    method_ = spemMethod::New(*case_, materials);
    method_->setUpWalls();
    method_->restoreSubCyclingLoad();
    // The bodies as given (t = 0), before a restart moves them
    checkBodiesAtStart();

    // Restart: the bodies' state (after the set-up, which uses their
    // configuration at t = 0)
    if (!bodies_.empty()) restart_.readBodies(bodies_);
    describe();
}


Foam::spemModel::~spemModel() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const Foam::elementModel& Foam::spemModel::elements() const
{
    if (!method_->elements())
    {
        FatalErrorInFunction
            << "This case has no elements (method " << methodName() << ')'
            << exit(FatalError);
    }
    return *method_->elements();
}


Foam::elementModel& Foam::spemModel::elements()
{
    std::as_const(*this).elements();
    return *method_->elements();
}


const Foam::sphFluid& Foam::spemModel::particles() const
{
    if (!method_->particles())
    {
        FatalErrorInFunction
            << "This case has no particles (method " << methodName() << ')'
            << exit(FatalError);
    }
    return *method_->particles();
}


void Foam::spemModel::evaluate()
{
    if (!method_->evaluate())
    {
        stopWithLastGoodState(method_->failure(), method_->failureHint());
    }
}


void Foam::spemModel::advance()
{
    if (!method_->advance(runTime_.deltaTValue()))
    {
        stopWithLastGoodState(method_->failure(), method_->failureHint());
    }
}


void Foam::spemModel::write(const bool force)
{
    if (!force && !runTime_.writeTime()) return;
    if (runTime_.value() == lastWrittenTime_) return;
    lastWrittenTime_ = runTime_.value();
    const costBreakdown::scope timed(cost(), costBreakdown::output);
    restart_.write(method_->state());
    vtk_->write(method_->elements(), method_->particles(), bodies_);
    if (force)
    {
        // Time's own record (uniform/time) for a restart from here
        runTime_.writeNow();
    }
}


// ************************************************************************* //
