#include "spemModel.H"
#include "initialDensity.H"
#include "Time.H"
#include "vectorIOField.H"
#include "uniformDimensionedFields.H"
#include "OSspecific.H"
#include "mathematicalConstants.H"
#include "vtkSeriesWriter.H"
#include "checkKeywords.H"
#include "elementToParticle.H"
#include "wallParticles.H"
#include "weaklyCompressibleNewtonian.H"
#include "scalarIOField.H"
#include "labelIOList.H"
#include "OFstream.H"
#include "sphKernel.H"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace Foam
{
    defineTypeNameAndDebug(spemModel, 0);
}

const Foam::Enum<Foam::spemModel::methodType>
Foam::spemModel::methodTypeNames
({
    { methodType::SPEM, "SPEM" },
    { methodType::SPH, "SPH" },
    { methodType::multiResolutionSPEM, "multiResolutionSPEM" },
});


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
        checkKeywords(bcDict.subDict(name), {"type"});
        patchTypes_[p] = patchTypeNames.get("type", bcDict.subDict(name));
    }
}


void Foam::spemModel::constrainElements()
{
    // Two slip walls meeting at more than this angle make a corner
    std::vector<elementModel::constraint> c;
    std::vector<scalar> normal;
    nodeConstraints
    (
        mesh_, patchTypes_, getOrDefault<scalar>("slipCornerAngle", 10),
        c, normal
    );
    elements_->setConstraints(std::move(c), std::move(normal));
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


void Foam::spemModel::readState()
{
    if (!elements_) return;

    IOobject xIO
    (
        "points", runTime_.timeName(), "spem", runTime_,
        IOobject::MUST_READ, IOobject::NO_WRITE, false
    );
    if (!xIO.typeHeaderOk<vectorIOField>(true)) return;

    IOobject vIO(xIO, "U");
    const vectorIOField xf(xIO);
    const vectorIOField vf(vIO);
    if (xf.size() != mesh_.nPoints() || vf.size() != mesh_.nPoints())
    {
        FatalErrorInFunction
            << "Restart state in " << xIO.path() << " has " << xf.size()
            << " points and " << vf.size() << " velocities; the mesh has "
            << mesh_.nPoints() << " nodes" << exit(FatalError);
    }
    std::vector<scalar> x(2*xf.size()), v(2*vf.size());
    forAll(xf, i)
    {
        x[2*i] = xf[i].x();
        x[2*i + 1] = xf[i].y();
        v[2*i] = vf[i].x();
        v[2*i + 1] = vf[i].y();
    }
    elements_->setState(x, v);
    Info<< "Restart: read node positions and velocities from "
        << xIO.path() << nl << endl;
}


void Foam::spemModel::writeState() const
{
    mkDir(runTime_.timePath()/"spem");
    if (particles_) writeParticleState();
    // The moving walls' accelerations, for an exact restart
    const auto writeAcceleration =
        [this](const word& name, const wallAcceleration& wa)
        {
            IOobject uIO
            (
                name + "OldU", runTime_.timeName(), "spem", runTime_,
                IOobject::NO_READ, IOobject::NO_WRITE, false
            );
            vectorIOField U(uIO, wa.size());
            vectorIOField A(IOobject(uIO, name + "Acceleration"), wa.size());
            forAll(U, k)
            {
                U[k] = vector(wa.oldVelocities()[2*k], wa.oldVelocities()[2*k + 1], 0);
                A[k] = vector(wa.accelerations()[2*k], wa.accelerations()[2*k + 1], 0);
            }
            U.write();
            A.write();
        };
    if (structureCoupling_)
    {
        writeAcceleration("virtualParticle", structureCoupling_->acceleration());
    }
    if (bodyCoupling_)
    {
        writeAcceleration("bodyParticle", bodyCoupling_->acceleration());
    }
    if (!bodies_.empty())
    {
        IOdictionary state
        (
            IOobject
            (
                "rigidBodies", runTime_.timeName(), "spem", runTime_,
                IOobject::NO_READ, IOobject::NO_WRITE, false
            )
        );
        bodies_.writeState(state);
        // All digits: the restart continues the same motion exactly
        OFstream os(state.objectPath());
        os.precision(17);
        state.writeHeader(os);
        state.writeData(os);
    }
    if (!elements_) return;

    if (bodyElements_)
    {
        labelIOList pairs
        (
            IOobject
            (
                "bodyNodes", runTime_.timeName(), "spem", runTime_,
                IOobject::NO_READ, IOobject::NO_WRITE, false
            ),
            2*bodyElements_->size()
        );
        for (label k = 0; k < bodyElements_->size(); ++k)
        {
            pairs[2*k] = bodyElements_->nodes()[k];
            pairs[2*k + 1] = bodyElements_->bodies()[k];
        }
        pairs.write();
    }

    if (!convertedTriangles_.empty())
    {
        labelIOList converted
        (
            IOobject
            (
                "convertedTriangles", runTime_.timeName(), "spem", runTime_,
                IOobject::NO_READ, IOobject::NO_WRITE, false
            ),
            label(convertedTriangles_.size())
        );
        forAll(converted, i) converted[i] = convertedTriangles_[i];
        converted.write();
    }

    const std::vector<scalar>& x = elements_->positions();
    const std::vector<scalar>& v = elements_->velocities();
    const label n = elements_->nNodes();

    IOobject xIO
    (
        "points", runTime_.timeName(), "spem", runTime_,
        IOobject::NO_READ, IOobject::NO_WRITE, false
    );
    vectorIOField xf(xIO, n);
    vectorIOField vf(IOobject(xIO, "U"), n);
    for (label i = 0; i < n; ++i)
    {
        xf[i] = vector(x[2*i], x[2*i + 1], 0);
        vf[i] = vector(v[2*i], v[2*i + 1], 0);
    }
    xf.write();
    vf.write();
}


void Foam::spemModel::writeVTK()
{
    std::vector<vtkOutput::triangleBlock> triangleBlocks;
    std::vector<vtkOutput::particleBlock> particleBlocks;

    // Element half. The arrays must live until the write below.
    std::vector<scalar> displacement, regionId;
    elementModel::elementFields f;
    if (elements_)
    {
        const elementModel& em = *elements_;
        const label nNodes = em.nNodes(), nEl = em.nElements();
        const std::vector<scalar>& x = em.positions();
        const std::vector<scalar>& X = em.referencePositions();

        displacement.resize(2*nNodes);
        for (label i = 0; i < 2*nNodes; ++i) displacement[i] = x[i] - X[i];
        regionId.resize(nEl);
        for (label r = 0; r < em.regions().size(); ++r)
        {
            const elementModel::region& reg = em.regions()[r];
            for (label e = reg.elemBegin; e < reg.elemEnd; ++e)
            {
                regionId[e] = r;
            }
        }
        f = em.fields();

        vtkOutput::triangleBlock elements;
        elements.name = "elements";
        elements.nPoints = nNodes;
        elements.points = x.data();
        elements.nTriangles = nEl;
        elements.triangles = em.elementNodes().data();
        elements.pointData =
        {
            {"velocity", 2, em.velocities().data()},
            {"displacement", 2, displacement.data()}
        };
        elements.cellData =
        {
            {"pressure", 1, f.pressure.data()},
            {"density", 1, f.density.data()},
            {"stress", 6, f.stress.data()},
            {"vonMisesStress", 1, f.vonMises.data()},
            {"region", 1, regionId.data()}
        };
        triangleBlocks.push_back(std::move(elements));
    }

    // Particle half: fluid particles and wall particles as two blocks
    // (gathered: the set interleaves them in cell order)
    struct gathered
    {
        std::vector<scalar> x, v, p, rho, h, surface, level, id;
    } fluid, wall;
    if (particles_)
    {
        const sphFluid& sph = *particles_;
        const particleSet& ps = sph.particles();
        for (label i = 0; i < ps.size(); ++i)
        {
            // Ghosts are the elements' state, which the elements show
            if (ps.kinds()[i] == particleSet::kind::ghost) continue;
            gathered& g =
                ps.kinds()[i] == particleSet::kind::fluid ? fluid : wall;
            g.x.push_back(ps.positions()[2*i]);
            g.x.push_back(ps.positions()[2*i + 1]);
            g.v.push_back(ps.velocities()[2*i]);
            g.v.push_back(ps.velocities()[2*i + 1]);
            g.p.push_back(ps.pressure()[i]);
            g.rho.push_back(ps.density()[i]);
            g.h.push_back(ps.smoothingLength()[i]);
            g.surface.push_back
            (
                ps.kinds()[i] == particleSet::kind::fluid
             && sph.freeSurface(i)
            );
            g.level.push_back(ps.level()[i]);
            g.id.push_back(ps.id()[i]);
        }

        vtkOutput::particleBlock fb;
        fb.name = "particles";
        fb.nParticles = fluid.p.size();
        fb.positions = fluid.x.data();
        fb.pointData =
        {
            {"velocity", 2, fluid.v.data()},
            {"pressure", 1, fluid.p.data()},
            {"density", 1, fluid.rho.data()},
            {"freeSurface", 1, fluid.surface.data()},
            {"smoothingLength", 1, fluid.h.data()},
            {"level", 1, fluid.level.data()},
            {"id", 1, fluid.id.data()}
        };
        particleBlocks.push_back(std::move(fb));

        // Walls: their pressure is the extrapolated one of the boundary
        // condition, useful to see the load on a wall
        vtkOutput::particleBlock wb;
        wb.name = "wallParticles";
        wb.nParticles = wall.p.size();
        wb.positions = wall.x.data();
        wb.pointData =
        {
            {"pressure", 1, wall.p.data()},
            {"density", 1, wall.rho.data()},
            {"smoothingLength", 1, wall.h.data()}
        };
        particleBlocks.push_back(std::move(wb));
    }

    // Rigid bodies: their outlines, moved, with the rigid velocity
    std::vector<scalar> bodyX, bodyV, bodyIndex;
    std::vector<label> bodyTri;
    if (!bodies_.empty())
    {
        if (bodyOutline_.empty())
        {
            forAll(bodies_, b)
            {
                // 96 points round a circle (its perimeter over 96); a
                // polygon's straight runs add points no triangle uses
                const scalar A = bodies_[b].shape().area();
                const scalar spacing =
                    std::sqrt(constant::mathematical::pi*A)/48;
                const rigidBodyShape& shape = bodies_[b].shape();
                bodyOutline_.push_back(shape.surfacePoints(spacing));
                bodyOutlineTriangles_.push_back
                (
                    rigidBodyShape::triangulate(bodyOutline_.back())
                );
            }
        }
        forAll(bodies_, b)
        {
            const rigidBody& body = bodies_[b];
            const label offset = label(bodyX.size()/2);
            const std::vector<scalar>& X = bodyOutline_[b];
            for (size_t i = 0; i < X.size()/2; ++i)
            {
                const vector2D x = body.toCurrent(vector2D(X[2*i], X[2*i + 1]));
                const vector2D v = body.velocityAt(x.x(), x.y());
                bodyX.push_back(x.x());
                bodyX.push_back(x.y());
                bodyV.push_back(v.x());
                bodyV.push_back(v.y());
            }
            for (const label n : bodyOutlineTriangles_[b])
            {
                bodyTri.push_back(offset + n);
            }
            bodyIndex.resize(bodyTri.size()/3, b);
        }
        vtkOutput::triangleBlock bb;
        bb.name = "rigidBodies";
        bb.nPoints = bodyX.size()/2;
        bb.points = bodyX.data();
        bb.nTriangles = bodyTri.size()/3;
        bb.triangles = bodyTri.data();
        bb.pointData = {{"velocity", 2, bodyV.data()}};
        bb.cellData = {{"body", 1, bodyIndex.data()}};
        triangleBlocks.push_back(std::move(bb));
    }

    try
    {
        // Created at the first write: on restart it drops the entries of the
        // existing series from the start time on
        if (!vtk_)
        {
            vtk_.reset
            (
                new vtkOutput::seriesWriter
                (
                    runTime_.path()/"VTK",
                    runTime_.caseName().name(),
                    runTime_.value()
                )
            );
        }
        vtk_->write(runTime_.value(), triangleBlocks, particleBlocks);
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "Writing the VTK series failed: " << err.what()
            << exit(FatalError);
    }
}


void Foam::spemModel::writeParticleState() const
{
    const particleSet& ps = particles_->particles();
    const label nFluid = particles_->nFluid();
    IOobject xIO
    (
        "particlePositions", runTime_.timeName(), "spem", runTime_,
        IOobject::NO_READ, IOobject::NO_WRITE, false
    );
    vectorIOField xf(xIO, nFluid);
    vectorIOField vf(IOobject(xIO, "particleU"), nFluid);
    scalarIOField rho(IOobject(xIO, "particleRho"), nFluid);
    scalarIOField rhoOld(IOobject(xIO, "particleRhoOld"), nFluid);
    scalarIOField m(IOobject(xIO, "particleMass"), nFluid);
    scalarIOField h(IOobject(xIO, "particleH"), nFluid);

    // In the order of the particle ids, so that a restart reproduces the
    // same particle set
    std::vector<label> order;
    for (label i = 0; i < ps.size(); ++i)
    {
        if (ps.kinds()[i] == particleSet::kind::fluid) order.push_back(i);
    }
    std::sort
    (
        order.begin(), order.end(),
        [&](const label a, const label b) { return ps.id()[a] < ps.id()[b]; }
    );
    forAll(xf, k)
    {
        const label i = order[k];
        xf[k] = vector(ps.positions()[2*i], ps.positions()[2*i + 1], 0);
        vf[k] = vector(ps.velocities()[2*i], ps.velocities()[2*i + 1], 0);
        rho[k] = ps.density()[i];
        rhoOld[k] = particles_->oldDensity()[i];
        m[k] = ps.mass()[i];
        h[k] = ps.smoothingLength()[i];
    }
    xf.write();
    vf.write();
    rho.write();
    rhoOld.write();
    m.write();
    h.write();
}


bool Foam::spemModel::readParticleState
(
    particleSet& particles,
    std::vector<scalar>& rhoOld
) const
{
    IOobject xIO
    (
        "particlePositions", runTime_.timeName(), "spem", runTime_,
        IOobject::MUST_READ, IOobject::NO_WRITE, false
    );
    if (!xIO.typeHeaderOk<vectorIOField>(true)) return false;

    const vectorIOField xf(xIO);
    const vectorIOField vf(IOobject(xIO, "particleU"));
    const scalarIOField rho(IOobject(xIO, "particleRho"));
    const scalarIOField m(IOobject(xIO, "particleMass"));
    const scalarIOField h(IOobject(xIO, "particleH"));
    const label n = xf.size();
    if (vf.size() != n || rho.size() != n || m.size() != n || h.size() != n)
    {
        FatalErrorInFunction
            << "Restart particle state in " << xIO.path() << " is"
            << " inconsistent: " << n << " positions, " << vf.size()
            << " velocities, " << rho.size() << " densities, " << m.size()
            << " masses, " << h.size() << " smoothing lengths"
            << exit(FatalError);
    }
    particles.reserve(n);
    forAll(xf, i)
    {
        particles.append
        (
            xf[i].x(), xf[i].y(), vf[i].x(), vf[i].y(), rho[i], 0, m[i], h[i]
        );
    }

    // Densities at the start of the step (volumes of the next evaluation);
    // a state without them restarts with the current ones
    IOobject oldIO(xIO, "particleRhoOld");
    rhoOld.assign(rho.begin(), rho.end());
    if (oldIO.typeHeaderOk<scalarIOField>(true))
    {
        const scalarIOField old(oldIO);
        if (old.size() == n) rhoOld.assign(old.begin(), old.end());
    }
    Info<< "Restart: read " << n << " fluid particles from " << xIO.path()
        << nl << endl;
    return true;
}


void Foam::spemModel::buildParticles
(
    const PtrList<spemMaterial>& materials,
    const std::vector<scalar>& density
)
{
    // The fluid regions: one fluid for the particles
    std::vector<label> fluidElements;
    const weaklyCompressibleNewtonian* fluid = nullptr;
    forAll(materials, r)
    {
        if (!materials.set(r)) continue;
        const spemMaterial& mat = materials[r];
        const auto* f = dynamic_cast<const weaklyCompressibleNewtonian*>(&mat);
        if (!f)
        {
            FatalIOErrorInFunction(*this)
                << "Region " << mesh_.regionNames()[r] << " (" << mat.type()
                << "): method SPH couples particles to solid regions, which"
                << " this version cannot do yet. Use method SPEM for"
                << " structures, or make the region a fluid or void"
                << exit(FatalIOError);
        }
        if (fluid && (f->rho() != fluid->rho() || f->c() != fluid->c()
                   || f->kinematicViscosity() != fluid->kinematicViscosity()))
        {
            FatalIOErrorInFunction(*this)
                << "Fluid regions with different rho, c or mu: the particle"
                << " half models one fluid" << exit(FatalIOError);
        }
        fluid = f;
        for (label t = 0; t < mesh_.nTriangles(); ++t)
        {
            if (mesh_.triangleRegion()[t] == r) fluidElements.push_back(t);
        }
    }
    // The water a body displaces at t = 0 is not there
    const std::vector<label> inside = trianglesInsideBodies();
    if (!inside.empty())
    {
        std::sort(fluidElements.begin(), fluidElements.end());
        std::vector<label> kept;
        std::set_difference
        (
            fluidElements.begin(), fluidElements.end(),
            inside.begin(), inside.end(), std::back_inserter(kept)
        );
        fluidElements.swap(kept);
    }
    if (!fluid)
    {
        FatalIOErrorInFunction(*this)
            << "method SPH needs at least one fluid region" << exit(FatalIOError);
    }

    // Eqs. (17-18): every fluid element becomes a particle at t = 0
    const std::vector<scalar>& x = mesh_.points();
    const std::vector<label>& tri = mesh_.triangles();
    std::vector<scalar> elementMass(mesh_.nTriangles(), 0);
    scalar areaSum = 0;
    for (const label t : fluidElements)
    {
        const scalar area = mesh_.triangleArea(t);
        elementMass[t] = density[t]*area;
        areaSum += area;
    }
    const sphFluid::controls ctrl = sphFluid::controls::read(schemes_);
    particleSet ps;
    std::vector<scalar> rhoOld;
    const bool restart = readParticleState(ps, rhoOld);
    if (restart)
    {
        if (ps.size() != label(fluidElements.size()))
        {
            FatalErrorInFunction
                << "The restart state of time " << runTime_.timeName()
                << " has " << ps.size() << " fluid particles; the mesh has "
                << fluidElements.size() << " fluid elements, each one"
                << " particle with method SPH. Is the state from another"
                << " mesh? (Allclean removes it.)" << exit(FatalError);
        }
    }
    else
    {
        const std::vector<scalar> v(x.size(), 0);
        appendParticlesFromElements
        (
            x, v, tri, elementMass, fluidElements, ctrl.smoothingLengthRatio, ps
        );
    }
    const label nFluid = ps.size();
    createParticleHalf
    (
        std::move(ps), std::move(rhoOld), *fluid,
        std::sqrt(areaSum/fluidElements.size())
    );
    Info<< "Particles (method SPH): " << nFluid << " fluid particles from "
        << fluidElements.size() << " fluid elements" << nl;

    // Initial relaxation of the barycentres (sphFluid.H), once, at t = 0;
    // a restart reads the relaxed positions
    if (ctrl.initialRelaxation > 0 && !restart)
    {
        const scalar lastShift = particles_->relax(ctrl.initialRelaxation);
        Info<< "    initial relaxation: " << ctrl.initialRelaxation
            << " iterations, last shift at most " << lastShift
            << " smoothing lengths" << nl;
    }
}


void Foam::spemModel::createParticleHalf
(
    particleSet&& ps,
    std::vector<scalar>&& rhoOld,
    const weaklyCompressibleNewtonian& fluid,
    const scalar spacing
)
{
    const sphFluid::controls ctrl = sphFluid::controls::read(schemes_);
    const std::vector<scalar>& x = mesh_.points();

    // Walls: dummy particles at the mean spacing of the fluid particles,
    // enough layers to fill the kernel support
    const scalar h = ctrl.smoothingLengthRatio*spacing;
    const scalar kappa = sphKernel::New(schemes_)->support();
    const label layers =
        ctrl.wallLayers > 0
      ? ctrl.wallLayers
      : label(std::ceil(kappa*ctrl.smoothingLengthRatio - 1e-9));
    const label nWall =
        appendWallParticles
        (
            mesh_, patchTypes_, spacing, layers, fluid.rho(), h, ps
        );

    // Lost particles: beyond the mesh's bounding box enlarged by
    // lostParticleDistance times its size on every side. Far enough for
    // splashes over an open top (the jet up the far wall of the damBreak
    // tutorial climbs to 2-3 tank heights), near enough to stop a
    // particle shot away by an unstable step before the neighbour search
    // has to cover its distance.
    const scalar lostParticleDistance = 3;
    scalar boxMin[2] = {GREAT, GREAT}, boxMax[2] = {-GREAT, -GREAT};
    for (label i = 0; i < mesh_.nPoints(); ++i)
    {
        for (int k = 0; k < 2; ++k)
        {
            boxMin[k] = min(boxMin[k], x[2*i + k]);
            boxMax[k] = max(boxMax[k], x[2*i + k]);
        }
    }
    for (int k = 0; k < 2; ++k)
    {
        const scalar size = boxMax[k] - boxMin[k];
        boxMin[k] -= lostParticleDistance*size;
        boxMax[k] += lostParticleDistance*size;
    }

    particles_.reset
    (
        new sphFluid
        (
            schemes_, std::move(ps), fluid.rho(), fluid.c(),
            fluid.rho()*fluid.kinematicViscosity(), g_[0], g_[1],
            boxMin, boxMax
        )
    );
    // Also on the restart path of method SPEM
    particles_->setMassDamping(massDamping_);

    // The rigid bodies seen by the particles
    if (!bodies_.empty())
    {
        bodyCoupling_.reset
        (
            new bodyParticleCoupling(bodies_, spacing, layers, fluid.rho(), h)
        );
        Info<< "    rigid bodies: " << bodyCoupling_->size()
            << " dummy particles" << nl;
    }

    // The solids seen by the particles (eq. 27)
    if (elements_)
    {
        structureCoupling_.reset
        (
            new structureParticleCoupling
            (
                mesh_, *elements_, patchTypes_, spacing, layers, fluid.rho(), h
            )
        );
        if (structureCoupling_->size() == 0)
        {
            structureCoupling_.reset();
        }
        else
        {
            Info<< "    structure-particle coupling: "
                << structureCoupling_->size()
                << " virtual particles in the solid regions" << nl;
        }
    }

    // Restart: the moving walls' accelerations of the written step
    const auto readAcceleration =
        [this](const word& name, wallAcceleration& wa)
        {
            IOobject uIO
            (
                name + "OldU", runTime_.timeName(), "spem", runTime_,
                IOobject::MUST_READ, IOobject::NO_WRITE, false
            );
            if (!uIO.typeHeaderOk<vectorIOField>(true)) return;
            const vectorIOField U(uIO);
            const vectorIOField A(IOobject(uIO, name + "Acceleration"));
            if (U.size() != wa.size() || A.size() != wa.size())
            {
                FatalErrorInFunction
                    << "The restart state " << uIO.objectPath() << " has "
                    << U.size() << " moving wall particles; the case has "
                    << wa.size() << ". Is the state from another mesh or"
                    << " body set-up? (Allclean removes it.)"
                    << exit(FatalError);
            }
            std::vector<scalar> u(2*U.size()), a(2*A.size());
            forAll(U, k)
            {
                u[2*k] = U[k].x();
                u[2*k + 1] = U[k].y();
                a[2*k] = A[k].x();
                a[2*k + 1] = A[k].y();
            }
            wa.restart(u, a);
        };
    if (structureCoupling_)
    {
        readAcceleration("virtualParticle", structureCoupling_->acceleration());
    }
    if (bodyCoupling_)
    {
        readAcceleration("bodyParticle", bodyCoupling_->acceleration());
    }

    if (!rhoOld.empty())
    {
        // Restart: the fluid particles come first; walls start at rho0
        rhoOld.resize(particles_->particles().size(), fluid.rho());
        particles_->setOldDensity(rhoOld);
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


void Foam::spemModel::setupConversion()
{
    const elementModel& em = *elements_;
    const label nTri = mesh_.nTriangles();
    std::vector<bool> fluidTri(nTri, false);
    scalar areaSum = 0, areaMax = 0;
    label nFluid = 0;
    for (label t = 0; t < nTri; ++t)
    {
        const label r = mesh_.triangleRegion()[t];
        if (!em.hasMaterial(r)) continue;   // void
        const spemMaterial& mat = em.material(r);
        if (!mat.isFluid()) continue;
        const auto* f = dynamic_cast<const weaklyCompressibleNewtonian*>(&mat);
        if (!f)
        {
            FatalErrorInFunction
                << "Fluid region " << mesh_.regionNames()[r] << " ("
                << mat.type() << ") cannot become particles" << exit(FatalError);
        }
        if
        (
            elementFluid_
         && (
                f->rho() != elementFluid_->rho() || f->c() != elementFluid_->c()
             || f->kinematicViscosity()
             != elementFluid_->kinematicViscosity()
            )
        )
        {
            FatalIOErrorInFunction(*this)
                << "Fluid regions with different rho, c or mu: the particles"
                << " of method SPEM model one fluid" << exit(FatalIOError);
        }
        elementFluid_ = f;
        fluidTri[t] = true;
        const scalar A = mesh_.triangleArea(t);
        areaSum += A;
        areaMax = max(areaMax, A);
        ++nFluid;
    }
    if (!elementFluid_) return;

    const scalar ratio =
        sphFluid::controls::read(schemes_).smoothingLengthRatio;
    fluidSpacing_ = std::sqrt(areaSum/nFluid);
    bodyReach_ =
        sphKernel::New(schemes_)->support()*ratio*fluidSpacing_;
    if (method_ == methodType::SPEM)
    {
        conversion_.reset
        (
            new groupConversion
            (
                schemes_.subOrEmptyDict("conversion"), mesh_, fluidTri,
                ratio*std::sqrt(areaMax), bodies_.surfaces()
            )
        );
        conversion_->describe(Info);
    }

    // Restart: the elements converted before, and their particles
    IOobject cIO
    (
        "convertedTriangles", runTime_.timeName(), "spem", runTime_,
        IOobject::MUST_READ, IOobject::NO_WRITE, false
    );
    if (cIO.typeHeaderOk<labelIOList>(true))
    {
        const labelIOList converted(cIO);
        convertedTriangles_.assign(converted.begin(), converted.end());
        if (convertedTriangles_.empty()) return;
        elements_->removeTriangles(mesh_, convertedTriangles_);
        particleSet ps;
        std::vector<scalar> rhoOld;
        if (!readParticleState(ps, rhoOld))
        {
            FatalErrorInFunction
                << cIO.objectPath() << " lists converted elements but "
                << runTime_.timePath()/"spem" << " has no particle state"
                << exit(FatalError);
        }
        createParticleHalf
        (
            std::move(ps), std::move(rhoOld), *elementFluid_, fluidSpacing_
        );
        coupling_.reset(new elementParticleCoupling(schemes_, ratio));
        coupling_->update(mesh_, *elements_, patchTypes_);
        return;
    }

    // method SPEM: the preset particle regions; method SPH: all the fluid
    std::vector<label> preset;
    if (conversion_)
    {
        preset = conversion_->presetTriangles(mesh_);
    }
    else
    {
        for (label t = 0; t < nTri; ++t)
        {
            if (fluidTri[t]) preset.push_back(t);
        }
    }
    // Not the triangles taken out already: those inside a rigid body at
    // t = 0 (a preset region around a body holds some)
    preset.erase
    (
        std::remove_if
        (
            preset.begin(), preset.end(),
            [&](const label t) { return elements_->removed(t); }
        ),
        preset.end()
    );
    if (!preset.empty())
    {
        convert(preset);
        Info<< "    " << (conversion_ ? "preset particle regions: " : "")
            << preset.size() << " fluid elements became particles at t = 0"
            << nl;
    }
}


void Foam::spemModel::convert(const std::vector<label>& triangles)
{
    const scalar ratio =
        sphFluid::controls::read(schemes_).smoothingLengthRatio;

    particleSet ps;
    convertElements(mesh_, triangles, ratio, *elements_, ps);
    convertedTriangles_.insert
    (
        convertedTriangles_.end(), triangles.begin(), triangles.end()
    );

    if (!particles_)
    {
        createParticleHalf
        (
            particleSet(), std::vector<scalar>(), *elementFluid_,
            fluidSpacing_
        );
        coupling_.reset(new elementParticleCoupling(schemes_, ratio));
    }
    particles_->appendFluid(ps);
    coupling_->update(mesh_, *elements_, patchTypes_);
    if (bodyElements_) bodyElements_->update(*elements_);

    Info<< "Conversion at time " << runTime_.timeName() << ": "
        << triangles.size() << " fluid elements became particles; "
        << elements_->nElements() << " elements, " << particles_->nFluid()
        << " particles, " << coupling_->nInterfaceSegments()
        << " interface segments" << nl;
}


std::vector<Foam::label> Foam::spemModel::trianglesInsideBodies() const
{
    std::vector<label> inside;
    if (bodies_.empty()) return inside;
    const std::vector<scalar>& X = mesh_.points();
    const std::vector<label>& tri = mesh_.triangles();
    // The fluid regions (the one fluid model), from the dictionary: the
    // materials may already belong to the element model
    const dictionary& regions = subDict("regions");
    std::vector<bool> fluidRegion(mesh_.nRegions(), false);
    forAll(mesh_.regionNames(), r)
    {
        const dictionary* rd = regions.findDict(mesh_.regionNames()[r]);
        fluidRegion[r] =
            rd && rd->get<word>("model") == "weaklyCompressibleNewtonian";
    }
    for (label t = 0; t < mesh_.nTriangles(); ++t)
    {
        if (!fluidRegion[mesh_.triangleRegion()[t]]) continue;
        const label* n = &tri[3*t];
        const scalar cx = (X[2*n[0]] + X[2*n[1]] + X[2*n[2]])/3;
        const scalar cy = (X[2*n[0] + 1] + X[2*n[1] + 1] + X[2*n[2] + 1])/3;
        forAll(bodies_, b)
        {
            if (bodies_[b].contains(cx, cy))
            {
                inside.push_back(t);
                break;
            }
        }
    }
    return inside;
}


Foam::bodyElementCoupling::preparedMesh Foam::spemModel::fitElementsToBodies
(
    const PtrList<spemMaterial>& materials
)
{
    const label nTri = mesh_.nTriangles();
    const std::vector<label>& tri = mesh_.triangles();
    std::vector<bool> fluid(nTri, false), fixedNode(mesh_.nPoints(), false);
    scalar areaSum = 0;
    label nFluid = 0;
    for (label t = 0; t < nTri; ++t)
    {
        const label r = mesh_.triangleRegion()[t];
        if (!materials.set(r)) continue;    // void: nothing to hold
        fluid[t] = materials[r].isFluid();
        if (fluid[t])
        {
            areaSum += mesh_.triangleArea(t);
            ++nFluid;
        }
        else
        {
            // A solid's nodes stay where the mesh has them
            for (label a = 0; a < 3; ++a) fixedNode[tri[3*t + a]] = true;
        }
    }
    if (nFluid == 0 || !bodies_.anySliding())
    {
        // Only the water inside the bodies goes
        bodyElementCoupling::preparedMesh inside;
        inside.removed = trianglesInsideBodies();
        return inside;
    }

    // Preset particle regions become particles at t = 0 as the mesh gives
    // them: not fitted, their nodes stay (the water inside a body is taken
    // out below)
    std::vector<bool> preset(nTri, false);
    {
        const PtrList<presetParticleRegion> regions =
            readPresetParticleRegions
            (
                schemes_.subOrEmptyDict("conversion"), mesh_,
                bodies_.surfaces()
            );
        const std::vector<scalar>& X = mesh_.points();
        for (label t = 0; t < nTri && !regions.empty(); ++t)
        {
            if (!fluid[t]) continue;
            const label* n = &tri[3*t];
            const scalar cx = (X[2*n[0]] + X[2*n[1]] + X[2*n[2]])/3;
            const scalar cy =
                (X[2*n[0] + 1] + X[2*n[1] + 1] + X[2*n[2] + 1])/3;
            for (const presetParticleRegion& r : regions)
            {
                if (r.contains(cx, cy))
                {
                    preset[t] = true;
                    fluid[t] = false;
                    for (label a = 0; a < 3; ++a) fixedNode[n[a]] = true;
                    break;
                }
            }
        }
    }

    // So do the nodes of walls and clamps; free-surface nodes may slide
    const std::vector<label>& seg = mesh_.segments();
    for (label s = 0; s < mesh_.nSegments(); ++s)
    {
        if (patchTypes_[mesh_.segmentPatch()[s]] != patchType::freeSurface)
        {
            fixedNode[seg[2*s]] = fixedNode[seg[2*s + 1]] = true;
        }
    }

    bodyContact_ = 0.25*std::sqrt(areaSum/nFluid);
    bodyElementCoupling::preparedMesh fitted =
        bodyElementCoupling::prepareMesh
        (
            mesh_, bodies_, fluid, fixedNode, bodyContact_
        );
    for (const label t : trianglesInsideBodies())
    {
        if (preset[t]) fitted.removed.push_back(t);
    }
    if (!fitted.nodes.empty())
    {
        Info<< "    rigid bodies: " << fitted.nodes.size() << " element nodes"
            << " moved onto their surfaces (at most " << fitted.maxMove
            << " m)" << nl;
    }
    return fitted;
}


void Foam::spemModel::bodyLoad(const label b, scalar F[2], scalar& M) const
{
    F[0] = F[1] = M = 0;
    if (bodyCoupling_)
    {
        F[0] += bodyCoupling_->force(b)[0];
        F[1] += bodyCoupling_->force(b)[1];
        M += bodyCoupling_->moment(b);
    }
    if (bodyElements_)
    {
        F[0] += bodyElements_->force(b)[0];
        F[1] += bodyElements_->force(b)[1];
        M += bodyElements_->moment(b);
    }
}


std::vector<Foam::label> Foam::spemModel::trianglesNearBodies() const
{
    std::vector<label> near;
    if (bodies_.empty() || !elements_ || !elementFluid_) return near;

    // fluidElements convert: elements with a node within the support of a
    // particle next to the body, converted before they can touch it.
    // slide: elements not on the body with a node within that support of
    // the body and of a particle next to it (a spacing from it)
    const elementModel& em = *elements_;
    const std::vector<scalar>& x = em.positions();
    const std::vector<label>& nodes = em.elementNodes();
    const scalar reach = bodyReach_;
    std::vector<scalar>& nextToBody = nextToBody_;
    forAll(bodies_, b)
    {
        const rigidBody& body = bodies_[b];
        const bool slide =
            body.elementsContact() == rigidBody::elementContact::slide;
        const boundBox box = body.boundingBox();
        if (slide)
        {
            if (!particles_ || !bodyElements_) continue;
            nextToBody.clear();
            const particleSet& ps = particles_->particles();
            const scalar* p = ps.positions().data();
            const scalar d = fluidSpacing_;
            for (label i = 0; i < ps.size(); ++i)
            {
                if (ps.kinds()[i] != particleSet::kind::fluid) continue;
                const scalar px = p[2*i], py = p[2*i + 1];
                if
                (
                    px < box.min().x() - d || px > box.max().x() + d
                 || py < box.min().y() - d || py > box.max().y() + d
                 || body.signedDistance(px, py) >= d
                )
                {
                    continue;
                }
                nextToBody.push_back(px);
                nextToBody.push_back(py);
            }
            if (nextToBody.empty()) continue;
        }
        for (label r = 0; r < em.regions().size(); ++r)
        {
            if (!em.hasMaterial(r) || !em.material(r).isFluid()) continue;
            for (label el = em.regions()[r].elemBegin; el < em.regions()[r].elemEnd; ++el)
            {
                const label* en = &nodes[3*el];
                if
                (
                    slide
                 && (
                        bodyElements_->attached(en[0])
                     || bodyElements_->attached(en[1])
                     || bodyElements_->attached(en[2])
                    )
                )
                {
                    continue;
                }
                for (label a = 0; a < 3; ++a)
                {
                    const scalar px = x[2*en[a]];
                    const scalar py = x[2*en[a] + 1];
                    if
                    (
                        px < box.min().x() - reach || px > box.max().x() + reach
                     || py < box.min().y() - reach || py > box.max().y() + reach
                     || body.signedDistance(px, py) >= reach
                    )
                    {
                        continue;
                    }
                    bool convert = !slide;
                    for (size_t k = 0; !convert && k < nextToBody.size()/2; ++k)
                    {
                        convert =
                            sqr(px - nextToBody[2*k]) + sqr(py - nextToBody[2*k + 1])
                          < sqr(reach);
                    }
                    if (convert)
                    {
                        near.push_back(em.elementTriangle()[el]);
                        break;
                    }
                }
            }
        }
    }
    return near;
}


void Foam::spemModel::setStructureParticles()
{
    if (!structureCoupling_ && !bodyCoupling_) return;
    structureX_.clear();
    structureV_.clear();
    structureA_.clear();
    structureM_.clear();
    structureH_.clear();
    if (structureCoupling_)
    {
        structureCoupling_->appendParticles
        (
            *elements_, lastDeltaT_, structureX_, structureV_, structureA_,
            structureM_, structureH_
        );
    }
    if (bodyCoupling_)
    {
        bodyCoupling_->appendParticles
        (
            bodies_, lastDeltaT_, structureX_, structureV_, structureA_,
            structureM_, structureH_
        );
    }
    particles_->setStructureParticles
    (
        label(structureM_.size()), structureX_.data(), structureV_.data(),
        structureA_.data(), structureM_.data(), structureH_.data()
    );
}


void Foam::spemModel::applyStructureForces()
{
    const scalar* F = particles_->structureParticleForce().data();
    const scalar* x = structureX_.data();
    if (structureCoupling_)
    {
        structureCoupling_->applyForces(*elements_, F);
        F += 2*structureCoupling_->size();
        x += 2*structureCoupling_->size();
    }
    if (bodyCoupling_) bodyCoupling_->applyForces(bodies_, x, F);
}


void Foam::spemModel::evaluateHalves(const bool correctInterface)
{
    if (conversion_)
    {
        const std::vector<label> tris =
            conversion_->trianglesToConvert(*elements_, trianglesNearBodies());
        if (!tris.empty()) convert(tris);
    }
    if (bodyElements_)
    {
        bodyElements_->attachNear(*elements_, bodies_, bodyContact_);
    }
    const bool coupled = elements_ && particles_ && coupling_;
    if (coupled)
    {
        coupling_->binParticles(*particles_);
        if (correctInterface && lastDeltaT_ > 0)
        {
            coupling_->correctVelocities(*elements_, *particles_, lastDeltaT_);
        }
    }
    if (elements_ && !elements_->evaluate())
    {
        stopWithLastGoodState(elements_->failure());
    }
    if (particles_)
    {
        if (coupled) coupling_->setGhosts(*elements_, *particles_);
        setStructureParticles();
        if (!particles_->evaluate())
        {
            stopWithLastGoodState(particles_->failure());
        }
        // The particles' forces on the elements: eq. (25) on the fluid
        // elements' interface (it sets the external forces), eq. (27) on
        // the solids (it adds to them) and on the bodies
        if (coupled) coupling_->interfaceTraction(*elements_, *particles_);
        applyStructureForces();
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemModel::spemModel(const Time& runTime)
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
    method_(methodTypeNames.get("method", schemes_)),
    mesh_(triMesh::read(runTime)),
    bodies_(runTime),
    elementFluid_(nullptr),
    fluidSpacing_(0),
    bodyReach_(0),
    bodyContact_(0),
    lastDeltaT_(0),
    massDamping_(0),
    lastWrittenTime_(-GREAT)
{
    checkKeywords
    (
        *this, {"regions", "boundaries", "damping", "slipCornerAngle"}
    );
    checkKeywords
    (
        schemes_, {"method", "kernel", "sph", "conversion", "coupling"}
    );
    if (method_ == methodType::multiResolutionSPEM)
    {
        FatalIOErrorInFunction(schemes_)
            << "method " << methodTypeNames[method_]
            << " is not available in this version; use SPEM or SPH"
            << exit(FatalIOError);
    }

    PtrList<spemMaterial> materials = readMaterials();
    bool anyMaterial = false;
    forAll(materials, r) anyMaterial = anyMaterial || materials.set(r);
    if (!anyMaterial)
    {
        FatalIOErrorInFunction(subDict("regions"))
            << "Every region is void (empty space): nothing to solve"
            << exit(FatalIOError);
    }

    const dictionary* dampingDict = findDict("damping");
    if (dampingDict) checkKeywords(*dampingDict, {"massProportional"});
    const scalar alpha =
        dampingDict
      ? dampingDict->getOrDefault<scalar>("massProportional", 0)
      : 0;
    if (alpha < 0)
    {
        FatalIOErrorInFunction(*dampingDict)
            << "massProportional must not be negative" << exit(FatalIOError);
    }
    massDamping_ = alpha;

    readBoundaries();
    readGravity();
    // Fluid elements fitted to the rigid bodies: before anything takes
    // masses or geometry from the mesh
    bodyElementCoupling::preparedMesh bodyMesh;
    if (method_ == methodType::SPEM && !bodies_.empty())
    {
        bodyMesh = fitElementsToBodies(materials);
    }
    // The state at t = 0 (a restart then overwrites what it stores)
    const std::vector<scalar> density =
        initialDensity
        (
            mesh_, patchTypes_, materials, subDict("regions"), g_[0], g_[1]
        );

    // Solids are elements with every method: method SPH converts all the
    // fluid at t = 0 and couples it to them (eq. 27)
    bool anySolid = false;
    forAll(materials, r)
    {
        anySolid = anySolid || (materials.set(r) && !materials[r].isFluid());
    }
    // The relaxation sees fluid and wall particles only: neither elements
    // (method SPEM, solid regions) nor the rigid bodies' dummy particles,
    // which are placed after it
    if
    (
        (method_ == methodType::SPEM || anySolid || !bodies_.empty())
     && sphFluid::controls::read(schemes_).initialRelaxation > 0
    )
    {
        FatalIOErrorInFunction(schemes_)
            << "sph/initialRelaxation relaxes the particles of method SPH"
            << " without solids or rigid bodies; with elements (method SPEM,"
            << " solid regions) or constant/rigidBodyProperties set it to 0"
            << exit(FatalIOError);
    }
    if (method_ == methodType::SPEM || anySolid)
    {
        elements_.reset
        (
            new elementModel(mesh_, std::move(materials), density)
        );
        constrainElements();
        elements_->setGravity(g_[0], g_[1]);
        elements_->setMassDamping(alpha);
        readState();
        // The water a body displaces at t = 0 is not there
        const std::vector<label> inside =
            method_ == methodType::SPEM
          ? bodyMesh.removed
          : trianglesInsideBodies();
        if (!inside.empty())
        {
            elements_->removeTriangles(mesh_, inside);
            Info<< "    rigid bodies: " << inside.size() << " fluid elements"
                << " inside them removed" << nl;
        }
        if (bodyContact_ > 0)
        {
            // Restart: the nodes attached then
            IOobject aIO
            (
                "bodyNodes", runTime_.timeName(), "spem", runTime_,
                IOobject::MUST_READ, IOobject::NO_WRITE, false
            );
            if (aIO.typeHeaderOk<labelIOList>(true))
            {
                const labelIOList pairs(aIO);
                bodyMesh.nodes.clear();
                bodyMesh.bodies.clear();
                for (label i = 0; i + 1 < pairs.size(); i += 2)
                {
                    bodyMesh.nodes.push_back(pairs[i]);
                    bodyMesh.bodies.push_back(pairs[i + 1]);
                }
                Info<< "Restart: read the element nodes on the rigid bodies"
                    << " from " << aIO.objectPath() << nl;
            }
            bodyElements_.reset
            (
                new bodyElementCoupling
                (
                    mesh_.nPoints(), bodies_.size(),
                    std::move(bodyMesh.nodes), std::move(bodyMesh.bodies)
                )
            );
        }
        setupConversion();
        if (bodyElements_)
        {
            // Without the nodes a restart's conversions left without
            // elements
            bodyElements_->update(*elements_);
            Info<< "    rigid bodies: " << bodyElements_->size()
                << " element nodes slide on them" << nl;
        }
    }
    else
    {
        buildParticles(materials, density);
        particles_->setMassDamping(alpha);
    }

    // Restart: the bodies' state (after the set-up, which uses their
    // configuration at t = 0)
    if (!bodies_.empty())
    {
        IOobject bIO
        (
            "rigidBodies", runTime_.timeName(), "spem", runTime_,
            IOobject::MUST_READ, IOobject::NO_WRITE, false
        );
        if (bIO.typeHeaderOk<IOdictionary>(true))
        {
            bodies_.readState(IOdictionary(bIO));
            Info<< "Restart: read the rigid bodies' state from "
                << bIO.objectPath() << nl;
        }
        forAll(bodies_, b)
        {
            Info<< "    rigid body " << bodies_[b].name() << ": "
                << bodies_[b].shape().type() << ", "
                << bodies_[b].motion().type() << nl;
        }
    }

    Info<< "Mesh: " << mesh_.nPoints() << " nodes, " << mesh_.nTriangles()
        << " triangles, " << mesh_.nSegments() << " boundary segments" << nl;
    if (elements_)
    {
        const elementModel& em = *elements_;
        for (const elementModel::region& r : em.regions())
        {
            const label ri = &r - em.regions().cdata();
            Info<< "    region " << r.name << ": "
                << (em.hasMaterial(ri) ? em.material(ri).type() : word("void"))
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
    if (alpha > 0)
    {
        Info<< "    mass-proportional damping " << alpha << " 1/s" << nl;
    }
    Info<< endl;
}


Foam::spemModel::~spemModel() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const Foam::elementModel& Foam::spemModel::elements() const
{
    if (!elements_)
    {
        FatalErrorInFunction
            << "This case has no elements (method "
            << methodTypeNames[method_] << ')' << exit(FatalError);
    }
    return *elements_;
}


Foam::elementModel& Foam::spemModel::elements()
{
    return const_cast<elementModel&>(std::as_const(*this).elements());
}


const Foam::sphFluid& Foam::spemModel::particles() const
{
    if (!particles_)
    {
        FatalErrorInFunction
            << "This case has no particles (method "
            << methodTypeNames[method_] << ')' << exit(FatalError);
    }
    return *particles_;
}


Foam::scalar Foam::spemModel::stableDeltaT() const
{
    scalar dt = GREAT;
    if (elements_) dt = min(dt, elements_->stableDeltaT());
    if (particles_) dt = min(dt, particles_->stableDeltaT());
    return dt;
}


void Foam::spemModel::stopWithLastGoodState(const std::string failure)
{
    // By value: re-evaluating the good state below clears the failure
    // message of the half that failed
    const std::string why = failure;
    const scalar tFail = runTime_.value();

    // The failed state is the current one; the previous one is good
    Time& runTime = const_cast<Time&>(runTime_);
    if (runTime.timeIndex() > runTime.startTimeIndex())
    {
        if (elements_) elements_->revert();
        if (particles_) particles_->revert();
        runTime.setTime(tFail - runTime.deltaTValue(), runTime.timeIndex() - 1);
        // Stresses and pressures of the good state for the output (it
        // evaluated before)
        if (elements_) elements_->evaluate();
        if (particles_) particles_->evaluate();
    }
    write(true);
    FatalErrorInFunction
        << "Run stopped at time " << tFail << ": " << why.c_str() << nl
        << "    The last good state (time " << runTime.timeName()
        << ") has been written to " << runTime.timePath()
        << " and VTK/." << nl
        << "    Reduce maxCo or deltaT, or check the set-up near the failure."
        << exit(FatalError);
}


void Foam::spemModel::evaluate()
{
    evaluateHalves(true);
}


void Foam::spemModel::advance()
{
    const scalar dt = runTime_.deltaTValue();
    if (bodyElements_) bodyElements_->constrain(*elements_, bodies_);
    if (elements_ && !elements_->advance(dt))
    {
        stopWithLastGoodState(elements_->failure());
    }
    if (bodyElements_) bodyElements_->gatherForces(*elements_, bodies_);
    if (particles_ && !particles_->advance(dt))
    {
        stopWithLastGoodState(particles_->failure());
    }
    // The bodies under the fluid's force of the last evaluation, from
    // t^n = t^{n+1} - dt (the Time is already at the new time)
    forAll(bodies_, b)
    {
        scalar F[2], M;
        bodyLoad(b, F, M);
        bodies_[b].advance(runTime_.value() - dt, dt, F[0], F[1], M, g_[0], g_[1]);
    }
    if (bodyElements_) bodyElements_->project(*elements_, bodies_);
    lastDeltaT_ = dt;
}


void Foam::spemModel::write(const bool force)
{
    if (!force && !runTime_.writeTime()) return;
    if (runTime_.value() == lastWrittenTime_) return;
    lastWrittenTime_ = runTime_.value();
    writeState();
    writeVTK();
    if (force)
    {
        // Time's own record (uniform/time) for a restart from here
        const_cast<Time&>(runTime_).writeNow();
    }
}


void Foam::spemModel::report(Ostream& os) const
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
    if (coupling_)
    {
        os  << ", ghost particles = " << particles_->nGhost()
            << ", interface segments = " << coupling_->nInterfaceSegments();
    }
    if (bodyElements_)
    {
        os  << ", element nodes on bodies = " << bodyElements_->size();
    }
    if (structureCoupling_)
    {
        const scalar* f = structureCoupling_->force();
        os  << ", force on solids = (" << f[0] << ' ' << f[1] << ')';
    }
    forAll(bodies_, b)
    {
        const rigidBody& body = bodies_[b];
        scalar f[2], m;
        bodyLoad(b, f, m);
        os  << ", body " << body.name() << " at (" << body.position().x()
            << ' ' << body.position().y() << ") velocity ("
            << body.velocity().x() << ' ' << body.velocity().y()
            << ") force (" << f[0] << ' ' << f[1] << ')';
    }
}


// ************************************************************************* //
