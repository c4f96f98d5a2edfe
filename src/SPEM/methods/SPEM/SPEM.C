#include "SPEM.H"
#include "initialDensity.H"
#include "sphKernel.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace spemMethods
{
    defineTypeNameAndDebug(SPEM, 0);
    addToRunTimeSelectionTable(spemMethod, SPEM, dictionary);
}
}


// * * * * * * * * * * * * Protected Member Functions  * * * * * * * * * * * //

void Foam::spemMethods::SPEM::collectCouplings()
{
    spemMethod::collectCouplings();
    // Body nodes first (their contact before eq. 26), then the interface:
    // eq. (25) before eq. (27) adds to the solids' external forces
    std::vector<spemCoupling*> first;
    if (bodyElements_) first.push_back(bodyElements_.get());
    if (coupling_) first.push_back(coupling_.get());
    couplings_.insert(couplings_.begin(), first.begin(), first.end());
}


void Foam::spemMethods::SPEM::recordCheckpoint()
{
    spemMethod::recordCheckpoint();
    if (bodyElements_)
    {
        checkpointBodyNodes_ = bodyElements_->nodes();
        checkpointNodeBodies_ = bodyElements_->bodies();
    }
}


void Foam::spemMethods::SPEM::undoEvaluation()
{
    spemMethod::undoEvaluation();
    if (bodyElements_)
    {
        bodyElements_->restore
        (
            checkpointBodyNodes_, checkpointNodeBodies_, *elements_
        );
    }
}


void Foam::spemMethods::SPEM::removeParticleHalf()
{
    coupling_.reset();
    spemMethod::removeParticleHalf();
}


void Foam::spemMethods::SPEM::evaluateLastGood()
{
    if (!coupling_)
    {
        spemMethod::evaluateLastGood();
        return;
    }
    // The ghosts of the failed evaluation stand for its elements: those of
    // the reverted ones instead, set as the step sets them but without
    // eq. (26), which the good state has had already
    elements_->evaluate();
    coupling_->binParticles(*particles_);
    coupling_->setGhosts(*elements_, *particles_);
    particles_->evaluate();
}


void Foam::spemMethods::SPEM::createParticleHalf
(
    particleSet&& ps,
    std::vector<scalar>&& rhoOld,
    const weaklyCompressibleNewtonian& fluid,
    const scalar spacing
)
{
    spemMethod::createParticleHalf
    (
        std::move(ps), std::move(rhoOld), fluid, spacing
    );
    coupling_.reset
    (
        new elementParticleCoupling
        (
            case_.schemes,
            sphFluid::controls::read(case_.schemes).smoothingLengthRatio,
            refinedRadiusRatio_
        )
    );
    collectCouplings();
}


std::vector<bool> Foam::spemMethods::SPEM::holdPresetTriangles
(
    std::vector<bool>& fluid,
    std::vector<bool>& fixedNode
) const
{
    // Preset particle regions become particles at t = 0 as the mesh gives
    // them: not fitted, their nodes stay (the water inside a body is taken
    // out after the fitting)
    const triMesh& mesh = case_.mesh;
    const label nTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();
    std::vector<bool> preset(nTri, false);
    const PtrList<presetParticleRegion> regions =
        readPresetParticleRegions
        (
            case_.schemes.subOrEmptyDict("conversion"), mesh,
            case_.bodies.surfaces()
        );
    const std::vector<scalar>& X = mesh.points();
    for (label t = 0; t < nTri && !regions.empty(); ++t)
    {
        if (!fluid[t]) continue;
        const label* n = &tri[3*t];
        const scalar cx = (X[2*n[0]] + X[2*n[1]] + X[2*n[2]])/3;
        const scalar cy = (X[2*n[0] + 1] + X[2*n[1] + 1] + X[2*n[2] + 1])/3;
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
    return preset;
}


Foam::bodyElementCoupling::preparedMesh
Foam::spemMethods::SPEM::fitElementsToBodies
(
    const PtrList<spemMaterial>& materials
)
{
    triMesh& mesh = case_.mesh;
    const label nTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();
    std::vector<bool> fluid(nTri, false), fixedNode(mesh.nPoints(), false);
    scalar areaSum = 0;
    label nFluid = 0;
    for (label t = 0; t < nTri; ++t)
    {
        const label r = mesh.triangleRegion()[t];
        if (!materials.set(r)) continue;    // void: nothing to hold
        fluid[t] = materials[r].isFluid();
        if (fluid[t])
        {
            areaSum += mesh.triangleArea(t);
            ++nFluid;
        }
        else
        {
            // A solid's nodes stay where the mesh has them
            for (label a = 0; a < 3; ++a) fixedNode[tri[3*t + a]] = true;
        }
    }
    if (nFluid == 0 || !case_.bodies.anySliding())
    {
        // Only the water inside the bodies goes
        bodyElementCoupling::preparedMesh inside;
        inside.removed = trianglesInsideBodies();
        return inside;
    }

    const std::vector<bool> preset = holdPresetTriangles(fluid, fixedNode);

    // So do the nodes of walls and clamps; free-surface nodes may slide
    const std::vector<label>& seg = mesh.segments();
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        if (case_.patchTypes[mesh.segmentPatch()[s]] != patchType::freeSurface)
        {
            fixedNode[seg[2*s]] = fixedNode[seg[2*s + 1]] = true;
        }
    }

    bodyContact_ =
        case_.bodies.elementContactDistance()*std::sqrt(areaSum/nFluid);
    bodyElementCoupling::preparedMesh fitted =
        bodyElementCoupling::prepareMesh
        (
            mesh, case_.bodies, fluid, fixedNode, bodyContact_
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


void Foam::spemMethods::SPEM::setupConversion()
{
    scalar maxArea;
    const std::vector<bool> fluidTri = surveyFluidElements(maxArea);
    if (!elementFluid_) return;

    const scalar ratio =
        sphFluid::controls::read(case_.schemes).smoothingLengthRatio;
    bodyReach_ =
        sphKernel::New(case_.schemes)->support()*ratio*fluidSpacing_;
    conversion_.reset
    (
        new groupConversion
        (
            case_.schemes.subOrEmptyDict("conversion"), case_.mesh, fluidTri,
            ratio*std::sqrt(maxArea), case_.bodies.surfaces()
        )
    );
    conversion_->describe(Info);
    findOpenStructureFaces();
    if (!openStructureFaces_.empty())
    {
        Info<< "    structures: fluid elements within "
            << conversion_->bodyReach()*bodyReach_ << " m in front of the "
            << openStructureFaces_.size()/3 << " open faces of the solid"
            << " regions become particles" << nl;
    }
    if (restartConversions()) return;

    // The preset particle regions, not the triangles taken out already:
    // those inside a rigid body at t = 0 (a preset region around a body
    // holds some)
    std::vector<label> preset = conversion_->presetTriangles(case_.mesh);
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
        Info<< "    preset particle regions: " << preset.size()
            << " fluid elements became particles at t = 0" << nl;
    }
}


bool Foam::spemMethods::SPEM::particlesNextTo
(
    const rigidBody& body,
    const scalar d
)
{
    nextToBody_.clear();
    const boundBox box = body.boundingBox();
    const particleSet& ps = particles_->particles();
    const scalar* p = ps.positions().data();
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
        nextToBody_.push_back(px);
        nextToBody_.push_back(py);
    }
    return !nextToBody_.empty();
}


template<class Fn>
void Foam::spemMethods::SPEM::forEachFluidElementOf
(
    const label n,
    Fn&& fn
) const
{
    // Through the node-element adjacency: a few per node instead of a pass
    // over every element
    const elementModel& em = *elements_;
    const std::vector<label>& start = em.nodeElementStart();
    const std::vector<label>& nodeElements = em.nodeElements();
    const std::vector<label>& triRegion = case_.mesh.triangleRegion();
    for (label j = start[n]; j < start[n + 1]; ++j)
    {
        const label el = nodeElements[j]/3;
        const label t = em.elementTriangle()[el];
        if (em.material(triRegion[t]).isFluid()) fn(el, t);
    }
}


std::vector<Foam::label> Foam::spemMethods::SPEM::trianglesNearBodies()
{
    std::vector<label> near;
    const rigidBodies& bodies = case_.bodies;
    if (bodies.empty() || !elements_ || !elementFluid_) return near;

    // fluidElements convert: elements with a node within the support of a
    // particle next to the body, converted before they can touch it.
    // slide: elements not on the body with a node within that support of
    // the body and of a particle next to it (a spacing from it)
    const elementModel& em = *elements_;
    const std::vector<scalar>& x = em.positions();
    const std::vector<label>& nodes = em.elementNodes();
    forAll(bodies, b)
    {
        const rigidBody& body = bodies[b];
        const bool slide =
            body.elementsContact() == rigidBody::elementContact::slide;
        // convert: the layer of conversion/bodyReach supports
        const scalar reach =
            slide ? bodyReach_ : conversion_->bodyReach()*bodyReach_;
        const boundBox box = body.boundingBox();
        if (slide)
        {
            if (!particles_ || !bodyElements_) continue;
            if (!particlesNextTo(body, fluidSpacing_)) continue;
        }
        const auto nearParticle = [&](const scalar px, const scalar py)
        {
            for (size_t k = 0; k < nextToBody_.size()/2; ++k)
            {
                if
                (
                    sqr(px - nextToBody_[2*k]) + sqr(py - nextToBody_[2*k + 1])
                  < sqr(reach)
                )
                {
                    return true;
                }
            }
            return false;
        };
        // The nodes in reach, each tested once (a node has about six
        // elements)
        const auto inReach = [&](const label n)
        {
            // slide: the elements of the nodes on the body stay elements
            if (slide && bodyElements_->attached(n)) return false;
            const scalar px = x[2*n];
            const scalar py = x[2*n + 1];
            if
            (
                px < box.min().x() - reach || px > box.max().x() + reach
             || py < box.min().y() - reach || py > box.max().y() + reach
             || body.signedDistance(px, py) >= reach
            )
            {
                return false;
            }
            return !slide || nearParticle(px, py);
        };
        nodesInReach_.clear();
        bodyBox_.assign
        (
            {
                box.min().x() - reach, box.min().y() - reach,
                box.max().x() + reach, box.max().y() + reach
            }
        );
        if (em.elementsNear(bodyBox_, elementsInBox_))
        {
            // The nodes of the elements over the box: every node in it
            // that has an element (a node without one has no element to
            // give), each once (the order does not matter: a set, for
            // trianglesToConvert)
            nodeSeen_.resize(em.nNodes(), 0);
            for (const label el : elementsInBox_)
            {
                for (label a = 0; a < 3; ++a)
                {
                    const label n = nodes[3*el + a];
                    if (nodeSeen_[n]) continue;
                    nodeSeen_[n] = 1;
                    if (inReach(n)) nodesInReach_.push_back(n);
                }
            }
            for (const label el : elementsInBox_)
            {
                for (label a = 0; a < 3; ++a) nodeSeen_[nodes[3*el + a]] = 0;
            }
        }
        else
        {
            // No grid (a node not finite): every node
            for (label n = 0; n < em.nNodes(); ++n)
            {
                if (inReach(n)) nodesInReach_.push_back(n);
            }
        }
        // Their fluid elements. An element with two nodes in reach comes
        // twice (a set: trianglesToConvert)
        for (const label n : nodesInReach_)
        {
            forEachFluidElementOf(n, [&](const label el, const label t)
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
                    return;
                }
                near.push_back(t);
            });
        }
    }
    return near;
}


void Foam::spemMethods::SPEM::findOpenStructureFaces()
{
    openStructureFaces_.clear();
    const triMesh& mesh = case_.mesh;
    const elementModel& em = *elements_;
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<label>& triRegion = mesh.triangleRegion();
    const std::vector<label>& edges = mesh.edges();
    const std::vector<label>& edgeTri = mesh.edgeTriangles();

    const auto solid = [&](const label t)
    {
        return
            t >= 0 && em.hasMaterial(triRegion[t])
         && !em.material(triRegion[t]).isFluid();
    };
    for (label k = 0; k < mesh.nEdges(); ++k)
    {
        for (label side = 0; side < 2; ++side)
        {
            const label t = edgeTri[2*k + side];
            if (!solid(t)) continue;
            // Open: the other side is a void region's triangle (a side on
            // the mesh's boundary faces nothing the fluid can cross the
            // mesh to: a plate's underside on a free-surface patch)
            const label other = edgeTri[2*k + 1 - side];
            if (other < 0 || em.hasMaterial(triRegion[other])) continue;
            const label a = edges[2*k], b = edges[2*k + 1];
            label c = -1;
            for (label i = 0; i < 3; ++i)
            {
                const label n = tri[3*t + i];
                if (n != a && n != b) c = n;
            }
            openStructureFaces_.push_back(a);
            openStructureFaces_.push_back(b);
            openStructureFaces_.push_back(c);
        }
    }
}


std::vector<Foam::label> Foam::spemMethods::SPEM::trianglesNearStructures()
{
    std::vector<label> near;
    const label nFaces = label(openStructureFaces_.size()/3);
    if (nFaces == 0 || !conversion_) return near;

    const elementModel& em = *elements_;
    const std::vector<scalar>& x = em.positions();
    const label* face = openStructureFaces_.data();
    const scalar reach = conversion_->bodyReach()*bodyReach_;

    // The faces' box widened by the reach: most nodes need no face test
    constexpr scalar big = std::numeric_limits<scalar>::max();
    scalar box[4] = {big, big, -big, -big};
    for (label f = 0; f < nFaces; ++f)
    {
        for (label i = 0; i < 2; ++i)
        {
            const label n = face[3*f + i];
            box[0] = std::min(box[0], x[2*n] - reach);
            box[1] = std::min(box[1], x[2*n + 1] - reach);
            box[2] = std::max(box[2], x[2*n] + reach);
            box[3] = std::max(box[3], x[2*n + 1] + reach);
        }
    }
    // A node within the reach of a face, on its open side (in front of
    // the line through it, away from the solid's third node)
    const auto inReach = [&](const scalar px, const scalar py)
    {
        for (label f = 0; f < nFaces; ++f)
        {
            const scalar* a = &x[2*face[3*f]];
            const scalar* b = &x[2*face[3*f + 1]];
            const scalar* c = &x[2*face[3*f + 2]];
            const scalar ex = b[0] - a[0], ey = b[1] - a[1];
            const scalar e2 = ex*ex + ey*ey;
            if (!(e2 > 0)) continue;
            // Normal ey, -ex, turned away from the solid
            const scalar side = ey*(c[0] - a[0]) - ex*(c[1] - a[1]);
            const scalar front = ey*(px - a[0]) - ex*(py - a[1]);
            if (!(front*side < 0)) continue;
            const scalar t = std::min
            (
                scalar(1),
                std::max(scalar(0), (ex*(px - a[0]) + ey*(py - a[1]))/e2)
            );
            if (sqr(px - a[0] - t*ex) + sqr(py - a[1] - t*ey) < sqr(reach))
            {
                return true;
            }
        }
        return false;
    };

    const std::vector<label>& start = em.nodeElementStart();
    for (label n = 0; n < em.nNodes(); ++n)
    {
        // Nodes of fluid elements only: a solid's own, or one left without
        // elements, is none
        if (em.solidNode(n) || start[n] == start[n + 1]) continue;
        const scalar px = x[2*n], py = x[2*n + 1];
        if (px < box[0] || px > box[2] || py < box[1] || py > box[3])
        {
            continue;
        }
        if (!inReach(px, py)) continue;
        forEachFluidElementOf
        (
            n, [&](const label, const label t) { near.push_back(t); }
        );
    }
    return near;
}


std::vector<Foam::label> Foam::spemMethods::SPEM::trianglesBehindWalls()
{
    std::vector<label> behind;
    if (!walls_) return behind;
    const elementModel& em = *elements_;
    // The free nodes of the fluid elements' boundary sides
    if (em.topologyVersion() != fluidBoundaryVersion_)
    {
        fluidBoundaryVersion_ = em.topologyVersion();
        fluidBoundaryNodes_.clear();
        const std::vector<label>& tri = case_.mesh.triangles();
        em.fluidBoundarySides(sideScratch_);
        std::vector<char> on(em.nNodes(), 0);
        for (const label side : sideScratch_)
        {
            const label t = side/3, i = side % 3;
            on[tri[3*t + i]] = on[tri[3*t + (i + 1) % 3]] = 1;
        }
        const std::vector<elementModel::constraint>& constraint =
            em.constraints();
        for (label n = 0; n < em.nNodes(); ++n)
        {
            if
            (
                on[n] && !em.solidNode(n)
             && constraint[n] == elementModel::constraint::free
            )
            {
                fluidBoundaryNodes_.push_back(n);
            }
        }
        if (!wallLookups_) wallLookups_.reset(new wallLookups(*walls_));
        wallLookups_->resize(em.nNodes());
    }

    // Each looked up again only once it has moved by its clearance, as
    // wallContact does for structure nodes
    const std::vector<scalar>& x = em.positions();
    tankBoundary::nearestPoint q;
    for (const label n : fluidBoundaryNodes_)
    {
        const wallLookups::place at =
            wallLookups_->lookUp(n, x[2*n], x[2*n + 1], q);
        // Grazing: a node that touches a wall by less than half a particle
        // spacing (damBreak: 10 um, at its back wall's foot) is left to
        // the distortion criterion
        if
        (
            at == wallLookups::place::clear
         || (
                at == wallLookups::place::behind
             && q.signedDistance < 0.5*fluidSpacing_
            )
        )
        {
            continue;
        }
        // Behind a wall (within reach or farther): its fluid elements
        forEachFluidElementOf
        (
            n, [&](const label, const label t) { behind.push_back(t); }
        );
    }
    return behind;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemMethods::SPEM::SPEM
(
    const spemCase& c,
    PtrList<spemMaterial>& materials
)
:
    SPEM(c, materials, 0)
{}


Foam::spemMethods::SPEM::SPEM
(
    const spemCase& c,
    PtrList<spemMaterial>& materials,
    const scalar refinedRadiusRatio
)
:
    spemMethod(c),
    bodyReach_(0),
    bodyContact_(0),
    fluidBoundaryVersion_(-1)
{
    refinedRadiusRatio_ = refinedRadiusRatio;
    const dictionary& conversionDict = c.schemes.subOrEmptyDict("conversion");
    if (refinedRadiusRatio_ == 0 && conversionDict.found("refinedRadiusRatio"))
    {
        FatalIOErrorInFunction(conversionDict)
            << "conversion/refinedRadiusRatio is an entry of method"
            << " multiResolutionSPEM: method " << c.schemes.get<word>("method")
            << " makes one particle per element" << exit(FatalIOError);
    }
    // Fluid elements fitted to the rigid bodies: before anything takes
    // masses or geometry from the mesh
    bodyElementCoupling::preparedMesh bodyMesh;
    if (!c.bodies.empty()) bodyMesh = fitElementsToBodies(materials);
    // The state at t = 0 (a restart then overwrites what it stores)
    const std::vector<scalar> density =
        initialDensity
        (
            c.mesh, c.patchTypes, materials, c.properties.subDict("regions"),
            c.g[0], c.g[1]
        );
    ignoreInitialRelaxation();
    createElementHalf(materials, density);

    // The water a body displaces at t = 0 is not there
    if (!bodyMesh.removed.empty())
    {
        elements_->removeTriangles(c.mesh, bodyMesh.removed);
        Info<< "    rigid bodies: " << bodyMesh.removed.size()
            << " fluid elements inside them removed" << nl;
    }
    if (bodyContact_ > 0)
    {
        // Restart: the nodes attached then
        c.restart.readBodyNodes(bodyMesh.nodes, bodyMesh.bodies);
        bodyElements_.reset
        (
            new bodyElementCoupling
            (
                c.mesh.nPoints(), c.bodies.size(),
                std::move(bodyMesh.nodes), std::move(bodyMesh.bodies),
                bodyContact_
            )
        );
        collectCouplings();
    }
    setupConversion();
    if (!coupling_)
    {
        // Made at the first conversion; its entries are checked now, not
        // writes later
        elementParticleCoupling
        (
            c.schemes, sphFluid::controls::read(c.schemes).smoothingLengthRatio,
            refinedRadiusRatio_
        );
    }
    if (bodyElements_)
    {
        // Without the nodes a restart's conversions left without elements
        bodyElements_->update(*elements_);
        Info<< "    rigid bodies: " << bodyElements_->size()
            << " element nodes slide on them" << nl;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::spemMethods::SPEM::evaluate()
{
    // What a failure of this evaluation undoes (revertToLastGood())
    recordCheckpoint();
    // Fluid elements that the last step took behind a wall (timed with the
    // elements: a look at their boundary nodes' motion, every step)
    std::vector<label> behindWalls;
    if (conversion_)
    {
        const costBreakdown::scope timed(cost_, costBreakdown::elements);
        behindWalls = trianglesBehindWalls();
    }
    // Nothing to check without a distortion criterion or bodies near which
    // elements convert: not even timed (see costBreakdown)
    if
    (
        conversion_
     && (
            conversion_->criterion().type() != "none"
         || !case_.bodies.empty() || !openStructureFaces_.empty()
         || !behindWalls.empty()
        )
    )
    {
        const costBreakdown::scope timed(cost_, costBreakdown::conversion);
        std::vector<label> forced = trianglesNearBodies();
        forced.insert(forced.end(), behindWalls.begin(), behindWalls.end());
        if (!openStructureFaces_.empty())
        {
            const std::vector<label> nearStructures = trianglesNearStructures();
            forced.insert
            (
                forced.end(), nearStructures.begin(), nearStructures.end()
            );
        }
        const std::vector<label> triangles =
            conversion_->trianglesToConvert(*elements_, forced);
        if (!triangles.empty()) convert(triangles);
    }
    return spemMethod::evaluate();
}


Foam::restartState::content Foam::spemMethods::SPEM::state() const
{
    restartState::content c = spemMethod::state();
    c.bodyNodes = bodyElements_.get();
    return c;
}


void Foam::spemMethods::SPEM::reportInterface(Ostream& os) const
{
    if (coupling_)
    {
        const scalar* d = coupling_->imbalance();
        os  << ", ghost particles = " << particles_->nGhost()
            << ", interface segments = " << coupling_->nInterfaceSegments();
        if (coupling_->nUnreachedInterfaceNodes() >= 0)
        {
            os  << ", interface nodes without particles = "
                << coupling_->nUnreachedInterfaceNodes();
        }
        os  << ", interface force imbalance = (" << d[0] << ' ' << d[1]
            << ')';
        if
        (
            coupling_->interfaceForce()
         == elementParticleCoupling::interfaceForceType::balancedFluid
        )
        {
            const scalar* D = coupling_->spread();
            os  << ", spread over the fluid = (" << D[0] << ' ' << D[1] << ')';
        }
    }
    if (bodyElements_)
    {
        os  << ", element nodes on bodies = " << bodyElements_->size();
    }
}


// ************************************************************************* //
