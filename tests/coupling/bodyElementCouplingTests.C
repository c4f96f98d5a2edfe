/*---------------------------------------------------------------------------*\
Description
    Unit tests of the fluid elements on rigid bodies
    (src/SPEM/coupling/bodyElementCoupling):
      - fitting a structured mesh to a circle leaves no staircase: every
        side of the fluid facing the body has both nodes on its surface,
        no fluid triangle is inside it or flattened, no free node is
        nearer than the snap distance, and the fluid area is the box minus
        the inscribed polygon of the nodes on the circle;
      - a body with fluidElements convert keeps the staircase of the
        triangles whose centroid is outside (nothing moves);
      - attached nodes slide: with the body moving, their velocity along
        the normal of the fluid's boundary (within a few degrees of the
        body's) is the body's and they stay on its surface; the load on the
        body is minus the sum of their constraint reactions.

\*---------------------------------------------------------------------------*/

#include "bodyElementCoupling.H"
#include "elementModel.H"
#include "IStringStream.H"
#include "mathematicalConstants.H"
#include "testMeshes.H"
#include "testModels.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

using namespace Foam;

namespace
{

const scalar R = 0.2, cx = 0.5, cy = 0.45;

//- The bodies from the text of the bodies dictionary's entries
rigidBodies bodiesFrom(const std::string& text)
{
    IStringStream is("bodies { " + text + " }");
    const dictionary dict(is);
    return rigidBodies(dict);
}

std::string circle(const std::string& extra = "")
{
    return
        "cylinder { shape circle; centre (" + std::to_string(cx) + ' '
      + std::to_string(cy) + " 0); radius " + std::to_string(R) + ";"
        " motion prescribed; velocity (0 0 0); " + extra + " }";
}

//- Water in the unit square, n x n cells; every triangle fluid, the
//  nodes of the box's sides fixed (walls)
struct waterBox
{
    triMesh mesh;
    std::vector<bool> fluid, fixed;
    scalar spacing;

    explicit waterBox(const int n)
    :
        mesh(testMeshes::build({{0, 1, 0, 1, n, n, "water"}})),
        fluid(mesh.nTriangles(), true),
        fixed(mesh.nPoints(), false),
        spacing(1.0/n)
    {
        for (label s = 0; s < mesh.nSegments(); ++s)
        {
            fixed[mesh.segments()[2*s]] = true;
            fixed[mesh.segments()[2*s + 1]] = true;
        }
    }
};

scalar distanceToCircle(const scalar x, const scalar y)
{
    return std::hypot(x - cx, y - cy) - R;
}

} // End anonymous namespace


TEST(BodyElementCoupling, fittedElementsFollowTheCircleWithoutAStaircase)
{
    waterBox box(40);
    const rigidBodies bodies = bodiesFrom(circle());
    const scalar snap = 0.25*box.spacing;
    std::vector<scalar> area0(box.mesh.nTriangles());
    for (label t = 0; t < box.mesh.nTriangles(); ++t)
    {
        area0[t] = box.mesh.triangleArea(t);
    }
    const bodyElementCoupling::preparedMesh fit =
        bodyElementCoupling::prepareMesh
        (
            box.mesh, bodies, box.fluid, box.fixed, snap
        );
    ASSERT_GT(fit.nodes.size(), 40u);
    EXPECT_LT(fit.maxMove, box.spacing);

    const triMesh& mesh = box.mesh;
    const std::vector<scalar>& x = mesh.points();
    std::vector<bool> removed(mesh.nTriangles(), false);
    for (const label t : fit.removed) removed[t] = true;
    std::vector<bool> onBody(mesh.nPoints(), false);
    for (size_t k = 0; k < fit.nodes.size(); ++k)
    {
        const label n = fit.nodes[k];
        EXPECT_EQ(fit.bodies[k], 0);
        EXPECT_NEAR(distanceToCircle(x[2*n], x[2*n + 1]), 0, 1e-12);
        onBody[n] = true;
    }

    // Kept triangles: outside, not flattened; sides used once
    std::map<std::pair<label, label>, int> sides;
    scalar area = 0;
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        if (removed[t]) continue;
        const label* n = &mesh.triangles()[3*t];
        const scalar A = mesh.triangleArea(t);
        EXPECT_GT(A, 0.2*area0[t]) << "triangle " << t;
        area += A;
        EXPECT_GT
        (
            distanceToCircle
            (
                (x[2*n[0]] + x[2*n[1]] + x[2*n[2]])/3,
                (x[2*n[0] + 1] + x[2*n[1] + 1] + x[2*n[2] + 1])/3
            ),
            0
        ) << "triangle " << t;
        for (label a = 0; a < 3; ++a)
        {
            const label p = n[a], q = n[(a + 1) % 3];
            if (!onBody[p])
            {
                EXPECT_GE(distanceToCircle(x[2*p], x[2*p + 1]), snap)
                    << "free node " << p;
            }
            ++sides[{std::min(p, q), std::max(p, q)}];
        }
    }

    // A side used once and not on the box is the fluid's side facing the
    // body: a chord of the circle, both ends on it
    label nFacing = 0;
    for (const auto& kv : sides)
    {
        if (kv.second != 1) continue;
        const label p = kv.first.first, q = kv.first.second;
        if (box.fixed[p] && box.fixed[q]) continue;
        ++nFacing;
        EXPECT_TRUE(onBody[p] && onBody[q])
            << "staircase: side " << p << '-' << q << " of the fluid is off"
            << " the body";
    }
    EXPECT_EQ(nFacing, label(fit.nodes.size()));

    // The fluid fills the box but the polygon of the nodes on the circle,
    // which is within 1 % of the circle
    std::vector<std::pair<scalar, label>> byAngle;
    for (const label n : fit.nodes)
    {
        byAngle.emplace_back(std::atan2(x[2*n + 1] - cy, x[2*n] - cx), n);
    }
    std::sort(byAngle.begin(), byAngle.end());
    scalar polygon = 0;
    for (size_t k = 0; k < byAngle.size(); ++k)
    {
        const label p = byAngle[k].second;
        const label q = byAngle[(k + 1) % byAngle.size()].second;
        polygon += 0.5*(x[2*p]*x[2*q + 1] - x[2*q]*x[2*p + 1]);
    }
    EXPECT_NEAR(area, 1 - polygon, 1e-12);
    const scalar circleArea = constant::mathematical::pi*R*R;
    EXPECT_NEAR(polygon, circleArea, 0.01*circleArea);
}


TEST(BodyElementCoupling, convertingBodyKeepsTheMeshAsItIs)
{
    waterBox box(40);
    const std::vector<scalar> before = box.mesh.points();
    const rigidBodies bodies = bodiesFrom(circle("fluidElements convert;"));
    const bodyElementCoupling::preparedMesh fit =
        bodyElementCoupling::prepareMesh
        (
            box.mesh, bodies, box.fluid, box.fixed, 0.25*box.spacing
        );
    EXPECT_TRUE(fit.nodes.empty());
    EXPECT_EQ(box.mesh.points(), before);
    // Only the triangles with their centroid inside go
    for (const label t : fit.removed)
    {
        const label* n = &box.mesh.triangles()[3*t];
        const std::vector<scalar>& x = box.mesh.points();
        EXPECT_LT
        (
            distanceToCircle
            (
                (x[2*n[0]] + x[2*n[1]] + x[2*n[2]])/3,
                (x[2*n[0] + 1] + x[2*n[1] + 1] + x[2*n[2] + 1])/3
            ),
            0
        );
    }
    EXPECT_FALSE(fit.removed.empty());
}


TEST(BodyElementCoupling, attachedNodesSlideWithTheMovingBodyAndLoadIt)
{
    // Water without gravity, the circle moving at (V, W) and turning: the
    // attached nodes keep the body's normal velocity and its surface
    waterBox box(30);
    const scalar V = 0.3, W = -0.2, omega = 0.5;
    rigidBodies bodies = bodiesFrom
    (
        "cylinder { shape circle; centre (" + std::to_string(cx) + ' '
      + std::to_string(cy) + " 0); radius " + std::to_string(R) + ";"
        " motion prescribed; velocity (" + std::to_string(V) + ' '
      + std::to_string(W) + " 0); angularVelocity "
      + std::to_string(omega) + "; }"
    );
    bodyElementCoupling::preparedMesh fit =
        bodyElementCoupling::prepareMesh
        (
            box.mesh, bodies, box.fluid, box.fixed, 0.25*box.spacing
        );
    std::unique_ptr<elementModel> em = testModels::model
    (
        box.mesh, {{"water", testModels::water}},
        {{"left", patchType::slipWall}, {"right", patchType::slipWall},
         {"bottom", patchType::slipWall}, {"top", patchType::slipWall}}
    );
    em->removeTriangles(box.mesh, fit.removed);
    bodyElementCoupling coupling
    (
        box.mesh.nPoints(), bodies.size(), fit.nodes, fit.bodies
    );
    coupling.update(*em);
    ASSERT_EQ(coupling.size(), label(fit.nodes.size()));

    const scalar dt = 1e-4;
    for (label step = 0; step < 50; ++step)
    {
        ASSERT_TRUE(em->evaluate()) << em->failure();
        coupling.constrain(*em, bodies);
        // The body's velocity at each node's closest point, before the
        // step, along the slip normal: that of the fluid's boundary, within
        // a few degrees of the body's
        std::vector<scalar> vn(coupling.size()), nx(coupling.size()), ny(coupling.size());
        for (label k = 0; k < coupling.size(); ++k)
        {
            const label n = coupling.nodes()[k];
            vector2D c, normal;
            bodies[0].signedDistance
            (
                em->positions()[2*n], em->positions()[2*n + 1], c, normal
            );
            nx[k] = em->slipNormals()[2*n];
            ny[k] = em->slipNormals()[2*n + 1];
            EXPECT_NEAR(std::hypot(nx[k], ny[k]), 1, 1e-12);
            EXPECT_GT(nx[k]*normal.x() + ny[k]*normal.y(), std::cos(0.2));
            const vector2D v = bodies[0].velocityAt(c.x(), c.y());
            vn[k] = v.x()*nx[k] + v.y()*ny[k];
        }
        ASSERT_TRUE(em->advance(dt));
        coupling.gatherForces(*em, bodies);
        scalar Fx = 0, Fy = 0;
        for (label k = 0; k < coupling.size(); ++k)
        {
            const label n = coupling.nodes()[k];
            const scalar* v = &em->velocities()[2*n];
            EXPECT_NEAR(v[0]*nx[k] + v[1]*ny[k], vn[k], 1e-12) << "node " << n;
            Fx -= em->constraintReactions()[2*n];
            Fy -= em->constraintReactions()[2*n + 1];
        }
        EXPECT_NEAR(coupling.force(0)[0], Fx, 1e-9*(1 + std::abs(Fx)));
        EXPECT_NEAR(coupling.force(0)[1], Fy, 1e-9*(1 + std::abs(Fy)));
        bodies[0].advance(step*dt, dt, 0, 0, 0, 0, 0);
        coupling.project(*em, bodies);
        for (const label n : coupling.nodes())
        {
            EXPECT_NEAR
            (
                bodies[0].signedDistance
                (
                    em->positions()[2*n], em->positions()[2*n + 1]
                ),
                0, 1e-12
            );
        }
        if (HasFailure()) return;
    }
    // The body pushed into the water ahead of it: the water resists
    EXPECT_GT(-(coupling.force(0)[0]*V + coupling.force(0)[1]*W), 0);
}


// ************************************************************************* //
