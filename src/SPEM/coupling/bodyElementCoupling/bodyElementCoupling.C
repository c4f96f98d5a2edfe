#include "bodyElementCoupling.H"
#include "mathematicalConstants.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- The smoothing of the band of fluid nodes round the sliding bodies
//  (bodyElementCoupling::smoothBand): the mesh, the bodies and what
//  prepareMesh decided, shared by its steps
class bandSmoother
{
    triMesh& mesh_;
    const rigidBodies& bodies_;
    const std::vector<bool>& fluid_;
    const std::vector<label>& outFor_;
    const std::vector<label>& nodeBody_;
    const std::vector<scalar>& area0_;
    const scalar snapDistance_;

public:

    //- Sweeps of the Gauss-Seidel smoothing
    static constexpr label nSweeps = 20;

    //- A triangle must keep this fraction of its area
    static constexpr scalar minAreaFraction = 0.2;

    bandSmoother
    (
        triMesh& mesh,
        const rigidBodies& bodies,
        const std::vector<bool>& fluid,
        const std::vector<label>& outFor,
        const std::vector<label>& nodeBody,
        const std::vector<scalar>& area0,
        const scalar snapDistance
    )
    :
        mesh_(mesh),
        bodies_(bodies),
        fluid_(fluid),
        outFor_(outFor),
        nodeBody_(nodeBody),
        area0_(area0),
        snapDistance_(snapDistance)
    {}

    //- True if triangle t is a fluid element kept in the model
    bool kept(const label t) const
    {
        return fluid_[t] && outFor_[t] < 0;
    }

    //- The band: free fluid nodes within bandWidth of a sliding body, and
    //  the nodes on the bodies (which stay on them)
    std::vector<label> band(const std::vector<bool>& fixedNode) const
    {
        const scalar bandWidth = 12*snapDistance_;     // three element spacings
        const label nPoints = mesh_.nPoints();
        const std::vector<label>& start = mesh_.nodeTriangleStart();
        const std::vector<label>& around = mesh_.nodeTriangles();

        std::vector<label> band;
        for (label n = 0; n < nPoints; ++n)
        {
            if (fixedNode[n]) continue;
            bool onlyKeptFluid = true, anyKept = false;
            for (label j = start[n]; j < start[n + 1]; ++j)
            {
                const label t = around[j]/3;
                anyKept = anyKept || kept(t);
                onlyKeptFluid = onlyKeptFluid && (kept(t) || (fluid_[t] && outFor_[t] >= 0));
            }
            if (!anyKept || !onlyKeptFluid) continue;
            if (nodeBody_[n] >= 0)
            {
                band.push_back(n);
                continue;
            }
            const scalar* p = &mesh_.points()[2*n];
            forAll(bodies_, b)
            {
                if
                (
                    bodies_[b].elementsContact() == rigidBody::elementContact::slide
                 && bodies_[b].signedDistance(p[0], p[1]) < bandWidth
                )
                {
                    band.push_back(n);
                    break;
                }
            }
        }
        return band;
    }

    //- Smallest interior angle of the kept triangles round node n with n
    //  at (px, py); -1 if one of them keeps less than minAreaFraction of
    //  its area
    scalar quality(const label n, const scalar px, const scalar py) const
    {
        const std::vector<label>& tri = mesh_.triangles();
        const std::vector<label>& start = mesh_.nodeTriangleStart();
        const std::vector<label>& around = mesh_.nodeTriangles();
        const std::vector<scalar>& x = mesh_.points();
        scalar worst = constant::mathematical::pi;
        for (label j = start[n]; j < start[n + 1]; ++j)
        {
            const label t = around[j]/3;
            if (!kept(t)) continue;
            scalar p[3][2];
            for (label a = 0; a < 3; ++a)
            {
                const label m = tri[3*t + a];
                p[a][0] = m == n ? px : x[2*m];
                p[a][1] = m == n ? py : x[2*m + 1];
            }
            const scalar twiceArea =
                (p[1][0] - p[0][0])*(p[2][1] - p[0][1])
              - (p[2][0] - p[0][0])*(p[1][1] - p[0][1]);
            if (0.5*twiceArea < minAreaFraction*area0_[t]) return scalar(-1);
            for (label a = 0; a < 3; ++a)
            {
                const scalar* o = p[a];
                const scalar* q = p[(a + 1) % 3];
                const scalar* r = p[(a + 2) % 3];
                const scalar ux = q[0] - o[0], uy = q[1] - o[1];
                const scalar vx = r[0] - o[0], vy = r[1] - o[1];
                worst = min
                (
                    worst,
                    std::atan2(std::abs(ux*vy - uy*vx), ux*vx + uy*vy)
                );
            }
        }
        return worst;
    }

    //- One Gauss-Seidel step of node n in the given sweep: toward the mean
    //  of its neighbours (a node on a body stays on it) as far as that
    //  raises the smallest angle round it
    void relaxNode(const label n, const label sweep)
    {
        const std::vector<label>& tri = mesh_.triangles();
        const std::vector<label>& start = mesh_.nodeTriangleStart();
        const std::vector<label>& around = mesh_.nodeTriangles();
        const std::vector<scalar>& x = mesh_.points();
        scalar sx = 0, sy = 0, w = 0;
        for (label j = start[n]; j < start[n + 1]; ++j)
        {
            const label t = around[j]/3, a = around[j] % 3;
            if (!kept(t)) continue;
            for (const label o : {tri[3*t + (a + 1) % 3], tri[3*t + (a + 2) % 3]})
            {
                sx += x[2*o];
                sy += x[2*o + 1];
                w += 1;
            }
        }
        if (w == 0) return;
        const scalar x0 = x[2*n], y0 = x[2*n + 1];
        scalar best = quality(n, x0, y0), bestX = x0, bestY = y0;
        // Toward the mean, and small steps round the node that shrink
        // with the sweeps (a hill climb on the smallest angle)
        const scalar step =
            0.8*snapDistance_*scalar(nSweeps - sweep)/nSweeps;
        const scalar candidates[11][2] =
        {
            {x0 + (sx/w - x0), y0 + (sy/w - y0)},
            {x0 + 0.5*(sx/w - x0), y0 + 0.5*(sy/w - y0)},
            {x0 + 0.25*(sx/w - x0), y0 + 0.25*(sy/w - y0)},
            {x0 + step, y0}, {x0 - step, y0},
            {x0, y0 + step}, {x0, y0 - step},
            {x0 + 0.7*step, y0 + 0.7*step}, {x0 - 0.7*step, y0 - 0.7*step},
            {x0 + 0.7*step, y0 - 0.7*step}, {x0 - 0.7*step, y0 + 0.7*step}
        };
        for (const auto& candidate : candidates)
        {
            scalar cx = candidate[0], cy = candidate[1];
            if (nodeBody_[n] >= 0)
            {
                vector2D closest, normal;
                bodies_[nodeBody_[n]].signedDistance(cx, cy, closest, normal);
                cx = closest.x();
                cy = closest.y();
            }
            else
            {
                // A free node stays as far from the bodies as the
                // snapping left it: nearer, it would attach at once
                bool tooNear = false;
                forAll(bodies_, b)
                {
                    tooNear = tooNear
                     || bodies_[b].signedDistance(cx, cy) < snapDistance_;
                }
                if (tooNear) continue;
            }
            const scalar q = quality(n, cx, cy);
            if (q > best)
            {
                best = q;
                bestX = cx;
                bestY = cy;
            }
        }
        mesh_.movePoint(n, bestX, bestY);
    }

    //- True if a kept triangle has less than minAreaFraction of its area
    bool spoiled() const
    {
        const label nTri = mesh_.nTriangles();
        for (label t = 0; t < nTri; ++t)
        {
            if (kept(t) && mesh_.triangleArea(t) < minAreaFraction*area0_[t])
            {
                return true;
            }
        }
        return false;
    }
};

//- The body each fluid triangle is left out for (-1: kept): the one its
//  centroid is in, the water the body displaces; area0: the areas of the
//  fluid triangles
std::vector<label> displacedTriangles
(
    const triMesh& mesh,
    const rigidBodies& bodies,
    const std::vector<bool>& fluid,
    std::vector<scalar>& area0
)
{
    const label nTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<scalar>& X = mesh.points();
    std::vector<label> outFor(nTri, -1);
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluid[t]) continue;
        area0[t] = mesh.triangleArea(t);
        const label* n = &tri[3*t];
        const scalar cx = (X[2*n[0]] + X[2*n[1]] + X[2*n[2]])/3;
        const scalar cy = (X[2*n[0] + 1] + X[2*n[1] + 1] + X[2*n[2] + 1])/3;
        forAll(bodies, b)
        {
            if (bodies[b].contains(cx, cy))
            {
                outFor[t] = b;
                break;
            }
        }
    }
    return outFor;
}


//- The sliding body each node is to be snapped to (-1: none): the free
//  nodes of kept triangles that are inside a sliding body or on a triangle
//  left out for one
std::vector<label> snapTargets
(
    const triMesh& mesh,
    const rigidBodies& bodies,
    const std::vector<bool>& fluid,
    const std::vector<label>& outFor,
    const scalar snapDistance
)
{
    const label nTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<scalar>& X = mesh.points();
    std::vector<label> target(mesh.nPoints(), -1);
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluid[t] || outFor[t] < 0) continue;
        const label b = outFor[t];
        if (bodies[b].elementsContact() != rigidBody::elementContact::slide)
        {
            continue;
        }
        for (label a = 0; a < 3; ++a) target[tri[3*t + a]] = b;
    }
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluid[t] || outFor[t] >= 0) continue;
        for (label a = 0; a < 3; ++a)
        {
            const label n = tri[3*t + a];
            forAll(bodies, b)
            {
                if
                (
                    bodies[b].elementsContact()
                 == rigidBody::elementContact::slide
                 && bodies[b].signedDistance(X[2*n], X[2*n + 1])
                  < snapDistance
                )
                {
                    target[n] = b;
                }
            }
        }
    }
    return target;
}


//- Leave out the kept triangles the moves flattened, inverted or closed
//  onto the surface (all three nodes on a body); true if any
bool leaveOutFlattened
(
    const triMesh& mesh,
    const std::vector<bool>& fluid,
    const std::vector<label>& nodeBody,
    const std::vector<scalar>& area0,
    std::vector<label>& outFor
)
{
    // A triangle snapped to less than this fraction of its area is left out
    constexpr scalar minAreaFraction = 0.2;

    const label nTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();
    bool leftOut = false;
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluid[t] || outFor[t] >= 0) continue;
        const label* n = &tri[3*t];
        const label nOn =
            (nodeBody[n[0]] >= 0) + (nodeBody[n[1]] >= 0)
          + (nodeBody[n[2]] >= 0);
        if (nOn == 0) continue;
        if (nOn == 3 || mesh.triangleArea(t) < minAreaFraction*area0[t])
        {
            for (label a = 0; a < 3; ++a)
            {
                if (nodeBody[n[a]] >= 0) outFor[t] = nodeBody[n[a]];
            }
            leftOut = true;
        }
    }
    return leftOut;
}


} // End anonymous namespace


// * * * * * * * * * * * * * * Static Member Functions * * * * * * * * * * * //

void Foam::bodyElementCoupling::smoothBand
(
    triMesh& mesh,
    const rigidBodies& bodies,
    const std::vector<bool>& fluid,
    const std::vector<bool>& fixedNode,
    const std::vector<label>& outFor,
    const std::vector<label>& nodeBody,
    const std::vector<scalar>& area0,
    const scalar snapDistance
)
{
    bandSmoother smoother
    (
        mesh, bodies, fluid, outFor, nodeBody, area0, snapDistance
    );
    const std::vector<label> band = smoother.band(fixedNode);
    if (band.empty()) return;

    const std::vector<scalar> before = mesh.points();

    // Gauss-Seidel sweeps: each node moves toward the mean of its
    // neighbours (a node on a body stays on it) as far as that raises the
    // smallest angle round it
    for (label sweep = 0; sweep < bandSmoother::nSweeps; ++sweep)
    {
        for (const label n : band)
        {
            smoother.relaxNode(n, sweep);
        }
    }

    // Smoothing must not spoil a triangle; if it does, the snapped mesh
    // stays as it was
    if (smoother.spoiled())
    {
        for (const label n : band)
        {
            mesh.movePoint(n, before[2*n], before[2*n + 1]);
        }
    }
}


Foam::bodyElementCoupling::preparedMesh
Foam::bodyElementCoupling::prepareMesh
(
    triMesh& mesh,
    const rigidBodies& bodies,
    const std::vector<bool>& fluid,
    const std::vector<bool>& fixedNode,
    const scalar snapDistance
)
{
    // Rounds of snapping and leaving out; a mesh needs two or three
    constexpr label maxRounds = 50;

    const label nTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();

    // The body each triangle is left out for (-1: kept), each node is on
    std::vector<scalar> area0(nTri, 0);
    std::vector<label> outFor = displacedTriangles(mesh, bodies, fluid, area0);
    std::vector<label> nodeBody(mesh.nPoints(), -1);
    const bool anySlide = bodies.anySliding();

    const std::vector<scalar>& X = mesh.points();
    preparedMesh result;
    for (label round = 0; anySlide && round < maxRounds; ++round)
    {
        // Move the free nodes of kept triangles that are inside a sliding
        // body or on a triangle left out for one
        const std::vector<label> target =
            snapTargets(mesh, bodies, fluid, outFor, snapDistance);
        bool moved = false;
        for (label t = 0; t < nTri; ++t)
        {
            if (!fluid[t] || outFor[t] >= 0) continue;
            for (label a = 0; a < 3; ++a)
            {
                const label n = tri[3*t + a];
                const label b = target[n];
                if (b < 0 || nodeBody[n] >= 0 || fixedNode[n]) continue;
                vector2D closest, normal;
                const scalar d = bodies[b].signedDistance
                (
                    X[2*n], X[2*n + 1], closest, normal
                );
                result.maxMove = max(result.maxMove, std::abs(d));
                mesh.movePoint(n, closest.x(), closest.y());
                nodeBody[n] = b;
                moved = true;
            }
        }

        // Leave out what the moves flattened, inverted or closed onto the
        // surface
        const bool leftOut =
            leaveOutFlattened(mesh, fluid, nodeBody, area0, outFor);
        if (!moved && !leftOut) break;
        if (round == maxRounds - 1)
        {
            FatalErrorInFunction
                << "Fitting the fluid elements to the rigid bodies did not"
                << " settle in " << maxRounds << " rounds" << exit(FatalError);
        }
    }

    if (anySlide) smoothBand(mesh, bodies, fluid, fixedNode, outFor, nodeBody, area0, snapDistance);

    // The nodes on a body that still have a fluid element
    std::vector<bool> used(mesh.nPoints(), false);
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluid[t]) continue;
        if (outFor[t] >= 0)
        {
            result.removed.push_back(t);
            continue;
        }
        for (label a = 0; a < 3; ++a) used[tri[3*t + a]] = true;
    }
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        if (nodeBody[n] >= 0 && used[n])
        {
            result.nodes.push_back(n);
            result.bodies.push_back(nodeBody[n]);
        }
    }
    return result;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::bodyElementCoupling::bodyElementCoupling
(
    const label nNodes,
    const label nBodies,
    std::vector<label> nodes,
    std::vector<label> bodies,
    const scalar contactDistance
)
:
    node_(std::move(nodes)),
    body_(std::move(bodies)),
    attached_(nNodes, false),
    solidNode_(nNodes, false),
    onAttachedElement_(nNodes, false),
    force_(2*nBodies, 0),
    moment_(nBodies, 0),
    contactDistance_(contactDistance)
{
    for (const label n : node_) attached_[n] = true;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::bodyElementCoupling::markElementsOf
(
    const label n,
    const elementModel& elements
)
{
    const std::vector<label>& start = elements.nodeElementStart();
    const std::vector<label>& around = elements.nodeElements();
    const std::vector<label>& nodes = elements.elementNodes();
    for (label j = start[n]; j < start[n + 1]; ++j)
    {
        const label e = around[j]/3;
        for (label a = 0; a < 3; ++a) onAttachedElement_[nodes[3*e + a]] = true;
    }
}


void Foam::bodyElementCoupling::restore
(
    const std::vector<label>& nodes,
    const std::vector<label>& bodies,
    const elementModel& elements
)
{
    for (const label n : node_) attached_[n] = false;
    node_ = nodes;
    body_ = bodies;
    for (const label n : node_) attached_[n] = true;
    update(elements);
}


void Foam::bodyElementCoupling::update(const elementModel& elements)
{
    const std::vector<scalar>& mass = elements.nodeMass();
    label kept = 0;
    for (label k = 0; k < size(); ++k)
    {
        if (mass[node_[k]] > 0)
        {
            node_[kept] = node_[k];
            body_[kept] = body_[k];
            ++kept;
        }
        else
        {
            attached_[node_[k]] = false;
        }
    }
    node_.resize(kept);
    body_.resize(kept);

    std::fill(onAttachedElement_.begin(), onAttachedElement_.end(), false);
    for (const label n : node_) markElementsOf(n, elements);

    // The solids' nodes (they never attach)
    std::fill(solidNode_.begin(), solidNode_.end(), false);
    const std::vector<label>& nodes = elements.elementNodes();
    for (const elementModel::region& r : elements.regions())
    {
        const label ri = &r - elements.regions().cdata();
        if (!elements.hasMaterial(ri) || elements.material(ri).isFluid())
        {
            continue;
        }
        for (label e = r.elemBegin; e < r.elemEnd; ++e)
        {
            for (label a = 0; a < 3; ++a) solidNode_[nodes[3*e + a]] = true;
        }
    }
}


Foam::label Foam::bodyElementCoupling::attachNear
(
    elementModel& elements,
    const rigidBodies& bodies,
    const scalar distance
)
{
    const std::vector<scalar>& x = elements.positions();
    const std::vector<scalar>& mass = elements.nodeMass();
    const std::vector<elementModel::constraint>& c = elements.constraints();
    label nAttached = 0;
    forAll(bodies, b)
    {
        const rigidBody& body = bodies[b];
        if (body.elementsContact() != rigidBody::elementContact::slide)
        {
            continue;
        }
        const boundBox box = body.boundingBox();
        const scalar x0 = box.min().x() - distance;
        const scalar x1 = box.max().x() + distance;
        const scalar y0 = box.min().y() - distance;
        const scalar y1 = box.max().y() + distance;
        for (label n = 0; n < elements.nNodes(); ++n)
        {
            const scalar px = x[2*n], py = x[2*n + 1];
            if (px < x0 || px > x1 || py < y0 || py > y1) continue;
            // Free fluid nodes only: not a wall's, not a solid's
            if
            (
                attached_[n] || mass[n] == 0 || solidNode_[n]
             || c[n] != elementModel::constraint::free
            )
            {
                continue;
            }
            vector2D closest, normal;
            if (body.signedDistance(px, py, closest, normal) >= distance)
            {
                continue;
            }
            elements.setPosition(n, closest.x(), closest.y());
            markElementsOf(n, elements);
            attached_[n] = true;
            node_.push_back(n);
            body_.push_back(b);
            ++nAttached;
        }
    }
    return nAttached;
}


void Foam::bodyElementCoupling::constrain
(
    elementModel& elements,
    const rigidBodies& bodies
) const
{
    const std::vector<scalar>& x = elements.positions();
    const std::vector<label>& start = elements.nodeElementStart();
    const std::vector<label>& around = elements.nodeElements();
    const std::vector<label>& nodes = elements.elementNodes();

    // Is the side (n, m) of the fluid's boundary (one element has it)?
    auto boundarySide = [&](const label n, const label m)
    {
        label nElements = 0;
        for (label j = start[n]; j < start[n + 1]; ++j)
        {
            const label* en = &nodes[3*(around[j]/3)];
            nElements += (en[0] == m || en[1] == m || en[2] == m);
        }
        return nElements == 1;
    };

    for (label k = 0; k < size(); ++k)
    {
        const label n = node_[k];
        const rigidBody& body = bodies[body_[k]];
        vector2D closest, normal;
        body.signedDistance(x[2*n], x[2*n + 1], closest, normal);

        // The slip direction is the normal of the fluid's own boundary at
        // the node (its sides on the body, length weighted: the direction
        // of the pressure's force on it), not the body's: on a curved body
        // the sides are chords, and the body's normal would leave the
        // node a tangential push from the pressure that no stiffness of a
        // fluid holds
        scalar nx = 0, ny = 0;
        for (label j = start[n]; j < start[n + 1]; ++j)
        {
            const label e = around[j]/3, a = around[j] % 3;
            // The element's sides from n and into n (counter-clockwise)
            const label next = nodes[3*e + (a + 1) % 3];
            const label prev = nodes[3*e + (a + 2) % 3];
            if (attached_[next] && boundarySide(n, next))
            {
                // Side n -> next, fluid on its left: into the fluid is
                // (-dy, dx)
                nx -= x[2*next + 1] - x[2*n + 1];
                ny += x[2*next] - x[2*n];
            }
            if (attached_[prev] && boundarySide(n, prev))
            {
                nx -= x[2*n + 1] - x[2*prev + 1];
                ny += x[2*n] - x[2*prev];
            }
        }
        const scalar length = std::hypot(nx, ny);
        if (length > 0 && nx*normal.x() + ny*normal.y() > 0)
        {
            normal = vector2D(nx/length, ny/length);
        }
        const vector2D v = body.velocityAt(closest.x(), closest.y());
        elements.setMovingSlip
        (
            n, normal.x(), normal.y(), v.x()*normal.x() + v.y()*normal.y()
        );
    }
}


void Foam::bodyElementCoupling::gatherForces
(
    const elementModel& elements,
    const rigidBodies& bodies
)
{
    std::fill(force_.begin(), force_.end(), 0);
    std::fill(moment_.begin(), moment_.end(), 0);
    const std::vector<scalar>& x = elements.positions();
    const std::vector<scalar>& R = elements.constraintReactions();
    for (label k = 0; k < size(); ++k)
    {
        const label n = node_[k], b = body_[k];
        const vector2D& c = bodies[b].position();
        // The body pushes the fluid with R: the fluid pushes back with -R
        const scalar Fx = -R[2*n], Fy = -R[2*n + 1];
        force_[2*b] += Fx;
        force_[2*b + 1] += Fy;
        moment_[b] += (x[2*n] - c.x())*Fy - (x[2*n + 1] - c.y())*Fx;
    }
}


void Foam::bodyElementCoupling::project
(
    elementModel& elements,
    const rigidBodies& bodies
) const
{
    const std::vector<scalar>& x = elements.positions();
    for (label k = 0; k < size(); ++k)
    {
        const label n = node_[k];
        vector2D closest, normal;
        bodies[body_[k]].signedDistance(x[2*n], x[2*n + 1], closest, normal);
        elements.setPosition(n, closest.x(), closest.y());
    }
}


// * * * * * * * * * * * * * * * * * * Hooks * * * * * * * * * * * * * * * * //

void Foam::bodyElementCoupling::beforeElementAdvance(couplingStep& s)
{
    constrain(*s.elements, s.bodies);
}


void Foam::bodyElementCoupling::afterElementAdvance(couplingStep& s)
{
    gatherForces(*s.elements, s.bodies);
}


void Foam::bodyElementCoupling::afterBodyAdvance(couplingStep& s)
{
    project(*s.elements, s.bodies);
}


void Foam::bodyElementCoupling::afterConversion(couplingStep& s)
{
    update(*s.elements);
}


void Foam::bodyElementCoupling::beforeElementEvaluate(couplingStep& s)
{
    attachNear(*s.elements, s.bodies, contactDistance_);
}


void Foam::bodyElementCoupling::addBodyLoad
(
    const label b,
    scalar F[2],
    scalar& M
) const
{
    addLoad(force_, moment_, b, F, M);
}


// ************************************************************************* //
