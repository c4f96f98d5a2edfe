#include "wallContact.H"

#include <cmath>
#include <sstream>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

//- For each element of the model: true if its region is a solid
std::vector<bool> solidElements(const Foam::elementModel& elements)
{
    std::vector<bool> solid(elements.nElements(), false);
    forAll(elements.regions(), r)
    {
        if (!elements.hasMaterial(r) || elements.material(r).isFluid())
        {
            continue;
        }
        const Foam::elementModel::region& reg = elements.regions()[r];
        for (Foam::label e = reg.elemBegin; e < reg.elemEnd; ++e)
        {
            solid[e] = true;
        }
    }
    return solid;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::wallContact::wallContact
(
    const tankBoundary& tank,
    const elementModel* elements,
    const rigidBodies& bodies
)
:
    tank_(tank),
    lookups_(tank),
    structureForce_{0, 0},
    bodyForce_(2*bodies.size(), 0),
    nNodeContacts_(0),
    nBodyContacts_(0)
{
    if (elements)
    {
        const std::vector<bool> solid = solidElements(*elements);
        std::vector<bool> onSolid(elements->nNodes(), false);
        const std::vector<label>& en = elements->elementNodes();
        for (label e = 0; e < elements->nElements(); ++e)
        {
            if (!solid[e]) continue;
            for (label i = 0; i < 3; ++i) onSolid[en[3*e + i]] = true;
        }
        for (label n = 0; n < elements->nNodes(); ++n)
        {
            if
            (
                onSolid[n]
             && elements->constraints()[n] != elementModel::constraint::fixed
            )
            {
                nodes_.push_back(n);
            }
        }
        lookups_.resize(label(nodes_.size()));
    }

    forAll(bodies, b)
    {
        bodyPoints0_.push_back
        (
            bodies[b].shape().surfacePoints(pointSpacing(tank_, bodies[b]))
        );
        bodyPoints_.push_back(bodyPoints0_.back());
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::wallContact::pointSpacing
(
    const tankBoundary& tank,
    const rigidBody& body
)
{
    const boundBox bb = body.boundingBox();
    return min(0.5*tank.reach(), 0.01*mag(bb.max() - bb.min()));
}


void Foam::wallContact::releaseSolidSlipNodes(elementModel& elements)
{
    const std::vector<bool> solid = solidElements(elements);
    std::vector<elementModel::constraint> c = elements.constraints();
    std::vector<scalar> normals = elements.slipNormals();
    const std::vector<label>& start = elements.nodeElementStart();
    const std::vector<label>& nodeElems = elements.nodeElements();
    bool changed = false;
    for (label n = 0; n < elements.nNodes(); ++n)
    {
        if (c[n] != elementModel::constraint::slip) continue;
        bool allSolid = start[n + 1] > start[n];
        for (label j = start[n]; j < start[n + 1] && allSolid; ++j)
        {
            allSolid = solid[nodeElems[j]/3];
        }
        if (!allSolid) continue;
        c[n] = elementModel::constraint::free;
        normals[2*n] = normals[2*n + 1] = 0;
        changed = true;
    }
    if (changed) elements.setConstraints(std::move(c), std::move(normals));
}


bool Foam::wallContact::correctStructures
(
    elementModel& elements,
    const scalar dt
)
{
    return correctStructures(elements, dt, true);
}


bool Foam::wallContact::correctStructures
(
    elementModel& elements,
    const scalar dt,
    const bool first
)
{
    if (first) structureForce_[0] = structureForce_[1] = 0;
    nNodeContacts_ = 0;
    const std::vector<scalar>& x = elements.positions();
    const std::vector<scalar>& v = elements.velocities();
    const std::vector<scalar>& m = elements.nodeMass();
    tankBoundary::nearestPoint q;

    // Performance critical: every structure node, every step (O(1) each)
    for (size_t i = 0; i < nodes_.size(); ++i)
    {
        const label n = nodes_[i];
        const scalar px = x[2*n], py = x[2*n + 1];
        const wallLookups::place at = lookups_.lookUp(label(i), px, py, q);
        if (at == wallLookups::place::clear) continue;
        if (at == wallLookups::place::behind)
        {
            ++nNodeContacts_;
            elements.setPosition(n, q.x, q.y);
            const scalar vn = v[2*n]*q.nx + v[2*n + 1]*q.ny;
            if (vn > 0)
            {
                elements.setNodeVelocity
                (
                    n, v[2*n] - vn*q.nx, v[2*n + 1] - vn*q.ny
                );
                // The wall's impulse over the step, as a force
                structureForce_[0] -= m[n]*vn*q.nx/dt;
                structureForce_[1] -= m[n]*vn*q.ny/dt;
            }
            continue;
        }
        // Farther than the tank's reach behind a wall
        std::ostringstream os;
        os  << "structure node " << n << " at (" << px << ' ' << py
            << ") went more than " << tank_.reach() << " m through a wall"
            << " in one step (velocity (" << v[2*n] << ' ' << v[2*n + 1]
            << "))";
        failure_ = os.str();
        return false;
    }
    return true;
}


bool Foam::wallContact::bodyContact
(
    rigidBody& body,
    const label b,
    const scalar dt
)
{
    std::vector<scalar>& P = bodyPoints_[b];
    const label nPoints = label(P.size()/2);
    tankBoundary::nearestPoint q;

    // Position: out along the normal of the deepest point, until none is
    // behind a wall (a corner may need a second move)
    for (label sweep = 0; sweep < impulseSweeps; ++sweep)
    {
        body.toCurrent(bodyPoints0_[b], P);
        scalar depth = 0, nx = 0, ny = 0;
        label deepest = -1;
        for (label i = 0; i < nPoints; ++i)
        {
            if (tank_.nearest(P[2*i], P[2*i + 1], q))
            {
                if (q.wall && q.signedDistance > depth)
                {
                    depth = q.signedDistance;
                    nx = q.nx;
                    ny = q.ny;
                    deepest = i;
                }
            }
            else if (tank_.outside(P[2*i], P[2*i + 1]))
            {
                depth = GREAT;
                deepest = i;
                break;
            }
        }
        if (deepest < 0) break;
        std::ostringstream os;
        os  << "rigid body " << body.name() << " at ("
            << body.position().x() << ' ' << body.position().y() << ')';
        if (depth == GREAT)
        {
            os  << " went more than " << tank_.reach() << " m through a wall"
                << " in one step (its point (" << P[2*deepest] << ' '
                << P[2*deepest + 1] << "))";
            failure_ = os.str();
            return false;
        }
        if (!body.motion().responds())
        {
            os  << " is " << depth << " m behind a wall at ("
                << P[2*deepest] << ' ' << P[2*deepest + 1] << "): its "
                << body.motion().type() << " motion takes it into the wall";
            failure_ = os.str();
            return false;
        }
        body.motion().translate(vector2D(-depth*nx, -depth*ny));
        ++nBodyContacts_;
    }
    body.toCurrent(bodyPoints0_[b], P);

    // Velocity: sequential impulses at the points on a wall moving into it
    const scalar touching = 1e-6*tank_.reach();
    const scalar e = body.wallRestitution();
    for (label sweep = 0; sweep < impulseSweeps; ++sweep)
    {
        bool any = false;
        for (label i = 0; i < nPoints; ++i)
        {
            const scalar px = P[2*i], py = P[2*i + 1];
            if
            (
                !tank_.nearest(px, py, q) || !q.wall
             || q.signedDistance < -touching
            )
            {
                continue;
            }
            const vector2D n(q.nx, q.ny), p(px, py);
            const scalar vn = body.velocityAt(px, py) & n;
            if (!(vn > 0)) continue;
            const scalar K = body.motion().inverseMassAlong(p, n);
            if (!(K > 0)) continue;
            const scalar J = (1 + e)*vn/K;
            body.motion().applyImpulse(p, -J*n);
            bodyForce_[2*b] -= J*n.x()/dt;
            bodyForce_[2*b + 1] -= J*n.y()/dt;
            any = true;
        }
        if (!any) break;
    }
    return true;
}


bool Foam::wallContact::correctBodies(rigidBodies& bodies, const scalar dt)
{
    nBodyContacts_ = 0;
    std::fill(bodyForce_.begin(), bodyForce_.end(), 0);
    forAll(bodies, b)
    {
        if (!bodyContact(bodies[b], b, dt)) return false;
    }
    return true;
}


// ************************************************************************* //
