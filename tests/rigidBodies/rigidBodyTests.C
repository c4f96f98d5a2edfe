/*---------------------------------------------------------------------------*\
Description
    Unit tests of the rigid bodies (src/SPEM/rigidBodies), each against a
    hand-computed or analytical answer:
      - polygon (square, rectangle, L with a concave corner, the 30 deg
        deadrise wedge) and circle: contains and signed distance, with the
        closest point and normal, inside, outside, near and on vertices and
        edges, before and after a translation and a 90 deg rotation;
      - the rigid velocity field equals the time derivative of a material
        point's position;
      - dummy particles: inside, not closer than spacing/2 to each other,
        every point within nLayers spacing of the surface within 0.75
        spacing of one (square, wedge, L, circle); a square gives the
        lattice; surface points and normals consistent; surface points
        spaced no more than spacing, on the surface, moved with the body;
      - free motion: free fall is exact (half kick at the first step),
        also with variable steps; held degrees of freedom keep their
        initial velocity; a constant moment gives theta = M t^2/(2 I);
        the default moment of inertia is that of a uniform body;
      - prescribed motion: constant velocity is exact; the table
        interpolates linearly, holds its end values, and moves the body by
        its integral;
      - bad dictionaries stop with a FatalIOError naming the keyword;
      - a restart through a written state continues bit for bit;
      - rigidBodies reads constant/rigidBodyProperties of a case.

\*---------------------------------------------------------------------------*/

#include "rigidBodies.H"
#include "freeMotion.H"
#include "prescribedMotion.H"
#include "dictionary.H"
#include "IStringStream.H"
#include "OStringStream.H"
#include "Time.H"
#include "mathematicalConstants.H"

#include "testDictionaries.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

using namespace Foam;

namespace
{

using testDictionaries::dictionaryFrom;
using testDictionaries::fatalIOErrorOf;

//- A body from the text of its dictionary
std::unique_ptr<rigidBody> bodyFrom(const std::string& text)
{
    return std::unique_ptr<rigidBody>
    (
        new rigidBody("test", dictionaryFrom(text))
    );
}

//- A body that does not move, with the given shape entries
std::unique_ptr<rigidBody> fixedBody(const std::string& shape)
{
    return bodyFrom(shape + " motion prescribed; velocity (0 0 0);");
}

const char* unitSquareClockwise =
    "shape polygon; points ((0 0 0) (0 1 0) (1 1 0) (1 0 0));";

const char* wedge =
    "shape polygon; points ((-0.25 0.1443 0) (0 0 0) (0.25 0.1443 0)"
    " (0.25 0.5 0) (-0.25 0.5 0));";

// L-shape: [0, 2]^2 without [1, 2]^2, concave corner at (1 1)
const char* lShape =
    "shape polygon; points ((0 0 0) (2 0 0) (2 1 0) (1 1 0) (1 2 0) (0 2 0));";

const scalar tol = 1e-12;

//- Expect the signed distance, closest point and normal at (x, y)
void expectDistance
(
    const rigidBody& body,
    const scalar x,
    const scalar y,
    const scalar distance,
    const vector2D& closest,
    const vector2D& normal
)
{
    SCOPED_TRACE
    (
        "at (" + std::to_string(x) + ", " + std::to_string(y) + ")"
    );
    vector2D c, n;
    EXPECT_NEAR(body.signedDistance(x, y), distance, tol);
    EXPECT_NEAR(body.signedDistance(x, y, c, n), distance, tol);
    EXPECT_NEAR(c.x(), closest.x(), tol);
    EXPECT_NEAR(c.y(), closest.y(), tol);
    EXPECT_NEAR(n.x(), normal.x(), tol);
    EXPECT_NEAR(n.y(), normal.y(), tol);
    // On the surface (to round-off) either answer is right
    if (std::abs(distance) > tol)
    {
        EXPECT_EQ(body.contains(x, y), distance < 0);
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * Shapes  * * * * * * * * * * * * * * * * //

TEST(RigidBodyShape, polygonSignedDistanceMatchesHandValuesInEitherOrientation)
{
    const auto square = fixedBody(unitSquareClockwise);
    EXPECT_EQ(square->shape().type(), "polygon");
    EXPECT_NEAR(square->shape().area(), 1, tol);

    expectDistance(*square, 0.5, 0.25, -0.25, {0.5, 0}, {0, -1});
    expectDistance(*square, 0.1, 0.2, -0.1, {0, 0.2}, {-1, 0});
    expectDistance(*square, 1.5, 0.5, 0.5, {1, 0.5}, {1, 0});
    // Outside near a vertex: closest is the vertex, normal towards the point
    expectDistance(*square, 1.3, 1.4, 0.5, {1, 1}, {0.6, 0.8});
    // On an edge and on a vertex: zero, not inside
    expectDistance(*square, 0.5, 1, 0, {0.5, 1}, {0, 1});
    expectDistance
    (
        *square, 1, 0, 0, {1, 0}, {std::sqrt(0.5), -std::sqrt(0.5)}
    );
    EXPECT_FALSE(square->contains(0.5, 1));
    EXPECT_FALSE(square->contains(0.5, 0));
    EXPECT_FALSE(square->contains(0, 0.5));
    EXPECT_FALSE(square->contains(1, 0));
    EXPECT_TRUE(square->contains(0.5, 1e-9));

    // Inside near the concave corner (1 1) of the L: the vertex is closest,
    // the outward normal points into the notch
    const auto L = fixedBody(lShape);
    expectDistance(*L, 0.8, 0.85, -0.25, {1, 1}, {0.8, 0.6});
    expectDistance(*L, 1.5, 1.5, 0.5, {1.5, 1}, {0, 1});
    EXPECT_FALSE(L->contains(1.01, 1.01));
    EXPECT_TRUE(L->contains(0.99, 1.5));

    // The wedge: below the keel, and above it off the axis, closest to the
    // bottom-right edge from (0 0) along e = (0.25, 0.1443)/|.|: distance
    // |e x p|, closest point (e.p) e, normal (e_y, -e_x)
    const auto w = fixedBody(wedge);
    expectDistance(*w, 0, -0.1, 0.1, {0, 0}, {0, -1});
    const vector2D e = vector2D(0.25, 0.1443)/std::hypot(0.25, 0.1443);
    const vector2D p(0.05, 0.1);
    expectDistance
    (
        *w, p.x(), p.y(), -(e.x()*p.y() - e.y()*p.x()),
        (e & p)*e,
        {e.y(), -e.x()}
    );
    EXPECT_TRUE(w->contains(0, 0.1));
    EXPECT_FALSE(w->contains(0.2, 0.05));
}


TEST(RigidBodyShape, circleSignedDistanceMatchesHandValues)
{
    const auto circle = fixedBody("shape circle; centre (1 -2 0); radius 0.5;");
    EXPECT_EQ(circle->shape().type(), "circle");
    expectDistance(*circle, 2, -2, 0.5, {1.5, -2}, {1, 0});
    expectDistance(*circle, 1, -1.8, -0.3, {1, -1.5}, {0, 1});
    expectDistance(*circle, 1.3, -2.4, 0, {1.3, -2.4}, {0.6, -0.8});
    EXPECT_FALSE(circle->contains(1, -1.5));   // on the circle, exactly
    expectDistance(*circle, 1, -2, -0.5, {1.5, -2}, {1, 0});   // centre
}


TEST(RigidBodyShape, queriesFollowATranslationAndA90DegRotation)
{
    // A 2 x 1 rectangle turned by 90 deg about its centre (1 0.5) and moved
    // by (1 0) in one step: it then covers [1.5, 2.5] x [-0.5, 1.5]
    auto rectangle = bodyFrom
    (
        "shape polygon; points ((0 0 0) (2 0 0) (2 1 0) (0 1 0));"
        "motion prescribed; velocity (1 0 0);"
        "angularVelocity 1.5707963267948966;"
    );
    rectangle->advance(0, 1, 0, 0, 0, 0, 0);
    EXPECT_NEAR(rectangle->position().x(), 2, tol);
    EXPECT_NEAR(rectangle->position().y(), 0.5, tol);
    EXPECT_NEAR(rectangle->angle(), M_PI/2, tol);

    expectDistance(*rectangle, 2, 1.4, -0.1, {2, 1.5}, {0, 1});
    expectDistance(*rectangle, 2, 1.6, 0.1, {2, 1.5}, {0, 1});
    expectDistance(*rectangle, 1.6, 0.5, -0.1, {1.5, 0.5}, {-1, 0});
    expectDistance(*rectangle, 2.8, -0.9, 0.5, {2.5, -0.5}, {0.6, -0.8});
    EXPECT_FALSE(rectangle->contains(0.5, 0.5));   // where it was
    EXPECT_FALSE(rectangle->contains(2.6, 0.5));

    const boundBox box = rectangle->boundingBox();
    EXPECT_NEAR(box.min().x(), 1.5, tol);
    EXPECT_NEAR(box.min().y(), -0.5, tol);
    EXPECT_NEAR(box.max().x(), 2.5, tol);
    EXPECT_NEAR(box.max().y(), 1.5, tol);

    // The reference corner (0 0) is now at (2.5 -0.5)
    const vector2D corner = rectangle->toCurrent(vector2D(0, 0));
    EXPECT_NEAR(corner.x(), 2.5, tol);
    EXPECT_NEAR(corner.y(), -0.5, tol);

    auto circle = bodyFrom
    (
        "shape circle; centre (0 0 0); radius 1;"
        "motion prescribed; velocity (0 2 0); angularVelocity 1.5707963267948966;"
    );
    circle->advance(0, 1, 0, 0, 0, 0, 0);
    expectDistance(*circle, 0, 3.5, 0.5, {0, 3}, {0, 1});
    expectDistance(*circle, 0.5, 2, -0.5, {1, 2}, {1, 0});
    EXPECT_NEAR(circle->boundingBox().min().y(), 1, tol);
}


TEST(RigidBodyShape, velocityFieldIsTheDerivativeOfMaterialPointPositions)
{
    auto body = bodyFrom
    (
        std::string(wedge)
      + "motion free; mass 241; initialVelocity (0.3 -0.2 0);"
        "initialAngularVelocity 2;"
    );
    const scalar h = 1e-5;
    for (int step = 0; step < 100; ++step)
    {
        body->advance(step*0.01, 0.01, 0, 0, 0, 0, 0);
    }
    for (const vector2D& X : {vector2D(0.2, 0.45), vector2D(0, 0), vector2D(-1, 3)})
    {
        const vector2D x0 = body->toCurrent(X);
        body->advance(1, h, 0, 0, 0, 0, 0);
        const vector2D x1 = body->toCurrent(X);
        // The field of the body as it is when the point is at x1
        const vector2D u = body->velocityAt(x1.x(), x1.y());
        body->advance(1 + h, h, 0, 0, 0, 0, 0);
        const vector2D x2 = body->toCurrent(X);

        const vector2D finiteDifference = (x2 - x0)/(2*h);
        EXPECT_NEAR(u.x(), finiteDifference.x(), 1e-7);
        EXPECT_NEAR(u.y(), finiteDifference.y(), 1e-7);
        EXPECT_GT(mag(u - vector2D(0.3, -0.2)), 0.1);  // rotation matters
    }
}


// * * * * * * * * * * * * * * * Dummy particles * * * * * * * * * * * * * * //

namespace
{

//- Check the dummy particles of the body: inside, apart, surface data
//  consistent, covering the layer band; prints the measured values
void expectWallParticlesFillTheBand
(
    const rigidBody& body,
    const scalar spacing,
    const label nLayers,
    const scalar maxGap = 0.75
)
{
    const bodyWallParticles particles = body.wallParticles(spacing, nLayers);
    const label n = particles.size();
    ASSERT_GT(n, 0);
    const std::vector<scalar>& X = particles.positions;

    scalar minDistance = GREAT;
    for (label i = 0; i < n; ++i)
    {
        EXPECT_TRUE(body.shape().contains(X[2*i], X[2*i + 1]))
            << "particle " << i << " (" << X[2*i] << ' ' << X[2*i + 1] << ')';
        for (label j = 0; j < i; ++j)
        {
            minDistance = std::min
            (
                minDistance,
                std::hypot(X[2*i] - X[2*j], X[2*i + 1] - X[2*j + 1])
            );
        }

        // The surface point is depth away along the normal
        EXPECT_NEAR
        (
            X[2*i] + particles.depths[i]*particles.normals[2*i],
            particles.surfacePoints[2*i], 1e-9
        );
        EXPECT_NEAR
        (
            X[2*i + 1] + particles.depths[i]*particles.normals[2*i + 1],
            particles.surfacePoints[2*i + 1], 1e-9
        );
        EXPECT_LE(particles.depths[i], (nLayers + 0.5)*spacing);
    }
    EXPECT_GE(minDistance, 0.5*spacing*(1 - 1e-9));

    // Every point of the band within nLayers spacing of the surface is
    // within maxGap spacing of a particle
    const boundBox box = body.shape().bounds(rigidTransform2D());
    const scalar step = spacing/7;
    scalar worst = 0;
    label nSamples = 0;
    for (scalar x = box.min().x() + 0.5*step; x < box.max().x(); x += step)
    {
        for (scalar y = box.min().y() + 0.5*step; y < box.max().y(); y += step)
        {
            const scalar d = body.shape().signedDistance(x, y);
            if (d >= 0 || d < -nLayers*spacing)
            {
                continue;
            }
            scalar nearest = GREAT;
            for (label i = 0; i < n; ++i)
            {
                nearest = std::min
                (
                    nearest, std::hypot(X[2*i] - x, X[2*i + 1] - y)
                );
            }
            worst = std::max(worst, nearest);
            ++nSamples;
        }
    }
    EXPECT_GT(nSamples, 100);
    EXPECT_LE(worst, maxGap*spacing);
    std::cout << body.shape().type() << ": " << n << " particles, closest "
        << minDistance/spacing << " spacing apart, farthest band point "
        << worst/spacing << " spacing from one (" << nSamples
        << " samples)" << std::endl;
}

} // End anonymous namespace


TEST(RigidBodyWallParticles, squareGivesTheLatticeOfItsBorderRing)
{
    const auto square = fixedBody(unitSquareClockwise);
    const bodyWallParticles particles = square->wallParticles(0.1, 2);
    // 10 x 10 lattice at (i + 1/2)/10 without its inner 6 x 6
    ASSERT_EQ(particles.size(), 64);
    for (label p = 0; p < particles.size(); ++p)
    {
        const scalar x = particles.positions[2*p], y = particles.positions[2*p + 1];
        const scalar i = 10*x - 0.5, j = 10*y - 0.5;
        EXPECT_NEAR(i, std::round(i), 1e-9);
        EXPECT_NEAR(j, std::round(j), 1e-9);
        const scalar depth = std::min(std::min(x, 1 - x), std::min(y, 1 - y));
        EXPECT_NEAR(particles.depths[p], depth, 1e-9);
        EXPECT_EQ(particles.layers[p], label(std::round(10*depth - 0.5)));
    }
}


TEST(RigidBodyWallParticles, squareParticlesAreInsideApartAndCoverTheBand)
{
    expectWallParticlesFillTheBand(*fixedBody(unitSquareClockwise), 0.07, 3);
}


TEST(RigidBodyWallParticles, wedgeParticlesAreInsideApartAndCoverTheBand)
{
    expectWallParticlesFillTheBand(*fixedBody(wedge), 0.02, 4);
    expectWallParticlesFillTheBand(*fixedBody(wedge), 0.013, 3);
}


TEST(RigidBodyWallParticles, concaveCornerParticlesAreInsideApartAndCoverTheBand)
{
    expectWallParticlesFillTheBand(*fixedBody(lShape), 0.1, 3);
}


TEST(RigidBodyWallParticles, circleParticlesAreInsideApartAndCoverTheBand)
{
    const auto circle = fixedBody("shape circle; centre (0 -1.25 0); radius 1;");
    expectWallParticlesFillTheBand(*circle, 0.05, 4);
    // Down to the centre
    expectWallParticlesFillTheBand(*circle, 0.23, 6);
}


TEST(RigidBodyWallParticles, sharpCornerTipIsFilledAlongItsBisector)
{
    // 20 deg tip at (0 0): the first layer's mitre point is 2.9 spacing in
    const auto spike = fixedBody
    (
        "shape polygon; points ((0 0 0) (1 -0.17632698 0) (1 0.17632698 0));"
    );
    const scalar spacing = 0.05;
    const bodyWallParticles particles = spike->wallParticles(spacing, 2);
    scalar nearestToTip = GREAT;
    for (label i = 0; i < particles.size(); ++i)
    {
        nearestToTip = std::min
        (
            nearestToTip,
            std::hypot(particles.positions[2*i], particles.positions[2*i + 1])
        );
    }
    EXPECT_LE(nearestToTip, 0.75*spacing);
    // Its 80 deg corners are 0.78 spacing from their mitre particles: a
    // corner sharper than 84 deg leaves a gap between 0.75 and 1 spacing
    expectWallParticlesFillTheBand(*spike, spacing, 1, 1.0);
}


TEST(RigidBodyWallParticles, placedByTheBodyWithoutRegeneration)
{
    auto body = bodyFrom
    (
        std::string(wedge)
      + "motion prescribed; velocity (0.5 -1 0); angularVelocity 0.7;"
    );
    const bodyWallParticles particles = body->wallParticles(0.02, 3);
    for (int step = 0; step < 10; ++step)
    {
        body->advance(0.1*step, 0.1, 0, 0, 0, 0, 0);
    }
    std::vector<scalar> x;
    body->toCurrent(particles.positions, x);
    ASSERT_EQ(x.size(), particles.positions.size());
    for (label i = 0; i < particles.size(); ++i)
    {
        // At its depth below the current surface
        EXPECT_NEAR
        (
            body->signedDistance(x[2*i], x[2*i + 1]), -particles.depths[i], 1e-9
        );
    }
}


TEST(RigidBodySurfacePoints, spacedNoMoreThanSpacingOnTheMovedSurface)
{
    for (const std::string& shape :
        {std::string(wedge), std::string(lShape),
         std::string("shape circle; centre (0 -1.25 0); radius 1;")})
    {
        SCOPED_TRACE(shape);
        auto body = bodyFrom
        (
            shape + "motion prescribed; velocity (1 2 0); angularVelocity 3;"
        );
        body->advance(0, 0.3, 0, 0, 0, 0, 0);
        const scalar spacing = 0.03;
        const std::vector<scalar> points = body->surfacePoints(spacing);
        const label n = label(points.size()/2);
        ASSERT_GT(n, 3);
        for (label i = 0; i < n; ++i)
        {
            const label j = (i + 1) % n;
            EXPECT_NEAR(body->signedDistance(points[2*i], points[2*i + 1]), 0, 1e-12);
            const scalar gap = std::hypot
            (
                points[2*j] - points[2*i], points[2*j + 1] - points[2*i + 1]
            );
            EXPECT_LE(gap, spacing*(1 + 1e-9));
            EXPECT_GT(gap, 0.5*spacing);
        }
    }
}


TEST(RigidBodySurfacePoints, outlineTriangulationCoversTheShapeExactly)
{
    // The ParaView outline: surface points triangulated by ear clipping.
    // Every triangle counter-clockwise, none overlapping (their areas add
    // up to the shape's: overlaps or gaps would change the sum), each
    // triangle's centroid inside the shape. The L has a reflex vertex and
    // points on straight runs, the square is given clockwise.
    for (const std::string& shape :
        {std::string(wedge), std::string(lShape),
         std::string(unitSquareClockwise),
         std::string("shape circle; centre (0 -1.25 0); radius 1;")})
    {
        SCOPED_TRACE(shape);
        auto body = fixedBody(shape);
        const std::vector<scalar> loop = body->surfacePoints(0.1);
        const std::vector<label> tri = rigidBodyShape::triangulate(loop);
        ASSERT_EQ(tri.size() % 3, 0u);
        ASSERT_GE(tri.size(), 3u);
        scalar area = 0;
        for (size_t t = 0; t < tri.size()/3; ++t)
        {
            const scalar* a = &loop[2*tri[3*t]];
            const scalar* b = &loop[2*tri[3*t + 1]];
            const scalar* c = &loop[2*tri[3*t + 2]];
            const scalar A =
                0.5*((b[0] - a[0])*(c[1] - a[1]) - (b[1] - a[1])*(c[0] - a[0]));
            EXPECT_GT(A, 1e-12) << "triangle " << t;
            area += A;
            EXPECT_TRUE
            (
                body->contains((a[0] + b[0] + c[0])/3, (a[1] + b[1] + c[1])/3)
            ) << "triangle " << t;
        }
        // The circle's outline is the inscribed polygon of its points
        const label n = label(loop.size()/2);
        scalar polygonArea = 0;
        for (label i = 0; i < n; ++i)
        {
            const label j = (i + 1) % n;
            polygonArea += 0.5*(loop[2*i]*loop[2*j + 1] - loop[2*j]*loop[2*i + 1]);
        }
        EXPECT_NEAR(area, std::abs(polygonArea), 1e-12);
        EXPECT_NEAR(area, body->shape().area(), 0.01*body->shape().area());
    }
}


// * * * * * * * * * * * * * * * * * Motion  * * * * * * * * * * * * * * * * //

TEST(RigidBodyFreeMotion, freeFallIsExactWithAHalfKickAtTheFirstStep)
{
    auto body = bodyFrom
    (
        std::string(unitSquareClockwise)
      + "motion free; mass 2; initialVelocity (0.5 1 0);"
    );
    const vector2D x0(0.5, 0.5), v0(0.5, 1), g(0.3, -9.81);

    // Constant steps, then varying ones: central differences with the
    // span (dt_old + dt_new)/2 stay exact for a constant acceleration
    scalar t = 0;
    for (int step = 0; step < 200; ++step)
    {
        const scalar deltaT = step < 100 ? 1e-3 : 1e-3*(1 + 0.5*std::sin(step));
        body->advance(t, deltaT, 0, 0, 0, g.x(), g.y());
        t += deltaT;
        if (step == 99 || step == 199)
        {
            const vector2D expected = x0 + v0*t + 0.5*g*t*t;
            EXPECT_NEAR(body->position().x(), expected.x(), 1e-13);
            EXPECT_NEAR(body->position().y(), expected.y(), 1e-13);
            // The velocity is the half step's
            const vector2D vHalf = v0 + g*(t - 0.5*deltaT);
            EXPECT_NEAR(body->velocity().x(), vHalf.x(), 1e-13);
            EXPECT_NEAR(body->velocity().y(), vHalf.y(), 1e-13);
        }
    }
    EXPECT_EQ(body->angle(), 0);
}


TEST(RigidBodyFreeMotion, forceOverMassAcceleratesLikeGravity)
{
    auto body = bodyFrom
    (
        std::string(unitSquareClockwise) + "motion free; mass 4;"
    );
    for (int step = 0; step < 50; ++step)
    {
        body->advance(step*0.01, 0.01, 8, -4, 0, 0, 0);
    }
    EXPECT_NEAR(body->position().x(), 0.5 + 0.5*2*0.25, 1e-13);
    EXPECT_NEAR(body->position().y(), 0.5 - 0.5*1*0.25, 1e-13);
    EXPECT_EQ(body->force().x(), 8);
    EXPECT_EQ(body->force().y(), -4);
}


TEST(RigidBodyFreeMotion, heldDegreesOfFreedomKeepTheirInitialVelocity)
{
    auto heldXAndRotation = bodyFrom
    (
        std::string(wedge)
      + "motion free; mass 241; initialVelocity (1 -6.15 0);"
        "constraints (x rotation);"
    );
    auto heldY = bodyFrom
    (
        std::string(wedge)
      + "motion free; mass 241; initialVelocity (1 -6.15 0); constraints (y);"
    );
    const vector2D c0 = heldXAndRotation->position();
    const scalar t = 0.1;
    for (int step = 0; step < 100; ++step)
    {
        heldXAndRotation->advance(step*1e-3, 1e-3, 1000, 500, 30, 2, -9.81);
        heldY->advance(step*1e-3, 1e-3, 1000, 500, 30, 2, -9.81);
    }
    // x at the initial speed, not rotated, y free: (500/241 - 9.81) t^2/2
    EXPECT_NEAR(heldXAndRotation->position().x(), c0.x() + 1*t, 1e-13);
    EXPECT_NEAR
    (
        heldXAndRotation->position().y(),
        c0.y() - 6.15*t + 0.5*(500.0/241 - 9.81)*t*t, 1e-12
    );
    EXPECT_EQ(heldXAndRotation->angle(), 0);
    EXPECT_EQ(heldXAndRotation->angularVelocity(), 0);

    EXPECT_NEAR(heldY->position().y(), c0.y() - 6.15*t, 1e-13);
    EXPECT_NEAR
    (
        heldY->position().x(), c0.x() + t + 0.5*(1000.0/241 + 2)*t*t, 1e-12
    );
    EXPECT_GT(heldY->angle(), 0);
}


TEST(RigidBodyFreeMotion, constantMomentTurnsByMomentTimesTimeSquaredOverTwoI)
{
    auto body = bodyFrom
    (
        std::string(lShape) + "motion free; mass 3; momentOfInertia 2;"
    );
    const vector2D c0 = body->position();
    const scalar M = 3, I = 2;
    for (int step = 0; step < 400; ++step)
    {
        body->advance(step*2.5e-3, 2.5e-3, 0, 0, M, 0, 0);
    }
    EXPECT_NEAR(body->angle(), M*1*1/(2*I), 1e-13);
    EXPECT_NEAR(body->moment(), M, 0);
    // Turning about the centre of mass, which stays put
    EXPECT_EQ(body->position().x(), c0.x());
    EXPECT_EQ(body->position().y(), c0.y());
}


TEST(RigidBodyFreeMotion, defaultsAreThoseOfAUniformBodyAtRest)
{
    // Unit square of mass 6: I = m (a^2 + b^2)/12 = 1 about its centroid;
    // about the corner (0 0): 1 + 6 (0.5^2 + 0.5^2) = 4
    auto square = bodyFrom(std::string(unitSquareClockwise) + "motion free; mass 6;");
    const auto& motion = dynamic_cast<const freeMotion&>(square->motion());
    EXPECT_NEAR(motion.momentOfInertia(), 1, 1e-13);
    EXPECT_EQ(square->position().x(), 0.5);
    EXPECT_EQ(square->position().y(), 0.5);
    EXPECT_EQ(square->velocity().x(), 0);
    EXPECT_EQ(square->angularVelocity(), 0);
    EXPECT_FALSE(motion.held(0) || motion.held(1) || motion.held(2));

    auto corner = bodyFrom
    (
        std::string(unitSquareClockwise)
      + "motion free; mass 6; centreOfMass (0 0 0);"
    );
    EXPECT_NEAR
    (
        dynamic_cast<const freeMotion&>(corner->motion()).momentOfInertia(),
        4, 1e-13
    );

    // Disc: m R^2/2
    auto disc = bodyFrom
    (
        "shape circle; centre (3 1 0); radius 2; motion free; mass 5;"
    );
    EXPECT_NEAR
    (
        dynamic_cast<const freeMotion&>(disc->motion()).momentOfInertia(),
        10, 1e-12
    );
    EXPECT_EQ(disc->position().x(), 3);
}


TEST(RigidBodyPrescribedMotion, constantVelocityMovesExactly)
{
    auto body = bodyFrom
    (
        "shape circle; centre (0 -1.25 0); radius 1;"
        "motion prescribed; velocity (0 0.39 0);"
    );
    EXPECT_EQ(body->velocity().y(), 0.39);   // before the first step too
    for (int step = 0; step < 1000; ++step)
    {
        body->advance(step*1e-3, 1e-3, 5, 6, 7, 0, -9.81);
    }
    EXPECT_NEAR(body->position().y(), -1.25 + 0.39, 1e-13);
    EXPECT_EQ(body->position().x(), 0);
    EXPECT_EQ(body->angle(), 0);
    // Loads are recorded, not applied
    EXPECT_EQ(body->force().y(), 6);
    EXPECT_EQ(body->moment(), 7);
}


TEST(RigidBodyPrescribedMotion, tableInterpolatesLinearlyAndHoldsItsEnds)
{
    auto body = bodyFrom
    (
        std::string(wedge)
      + "motion prescribed;"
        "velocityTable ((0 (0 0 0)) (0.1 (0 0.39 0)) (0.2 (0.1 0.39 0)));"
    );
    const auto& motion = dynamic_cast<const prescribedMotion&>(body->motion());
    auto expectVelocity = [&](const scalar t, const scalar u, const scalar v)
    {
        EXPECT_NEAR(motion.velocityAt(t).x(), u, 1e-15) << "t = " << t;
        EXPECT_NEAR(motion.velocityAt(t).y(), v, 1e-15) << "t = " << t;
    };
    expectVelocity(-1, 0, 0);
    expectVelocity(0, 0, 0);
    expectVelocity(0.05, 0, 0.195);
    expectVelocity(0.1, 0, 0.39);
    expectVelocity(0.15, 0.05, 0.39);
    expectVelocity(0.2, 0.1, 0.39);
    expectVelocity(5, 0.1, 0.39);

    // Mid-step velocities integrate a piecewise linear table exactly when
    // the steps do not straddle its times: 0.39*0.1/2 up to t = 0.1
    const vector2D c0 = body->position();
    for (int step = 0; step < 10; ++step)
    {
        body->advance(0.01*step, 0.01, 0, 0, 0, 0, 0);
    }
    EXPECT_NEAR(body->position().y() - c0.y(), 0.0195, 1e-15);
    EXPECT_NEAR(body->velocity().y(), 0.39*0.95, 1e-15);
}


// * * * * * * * * * * * * * * * * Dictionaries  * * * * * * * * * * * * * * //

TEST(RigidBodyDictionary, badValuesStopNamingTheKeyword)
{
    const std::string heavy = std::string(wedge) + " motion free;";

    fatalIOErrorOf
    (
        [&] { fixedBody("shape polygon; points ((0 0 0) (1 0 0));"); },
        {"points", "at least 3"}
    );
    fatalIOErrorOf
    (
        [&] { fixedBody("shape polygon; points ((0 0 0) (1 1 0) (2 2 0));"); },
        {"points", "no area"}
    );
    // Bow tie
    fatalIOErrorOf
    (
        [&] { fixedBody("shape polygon; points ((0 0 0) (2 2 0) (2 0 0) (0 1 0));"); },
        {"points", "self-intersecting"}
    );
    // Folds back along an edge
    fatalIOErrorOf
    (
        [&] { fixedBody("shape polygon; points ((0 0 0) (2 0 0) (1 0 0) (1 1 0));"); },
        {"points", "self-intersecting"}
    );
    // Touches itself at a vertex
    fatalIOErrorOf
    (
        [&]
        {
            fixedBody
            (
                "shape polygon;"
                "points ((0 0 0) (2 0 0) (1 1 0) (2 2 0) (0 2 0) (1 1 0));"
            );
        },
        {"points"}
    );
    fatalIOErrorOf
    (
        [&] { fixedBody("shape polygon; points ((0 0 0) (1 0 0) (1 0 0) (0 1 0));"); },
        {"points", "repeats"}
    );
    fatalIOErrorOf
    (
        [&] { fixedBody("shape circle; centre (0 0 0); radius 0;"); },
        {"radius"}
    );
    fatalIOErrorOf
    (
        [&] { fixedBody("shape circle; centre (0 0 0); radius -1;"); },
        {"radius"}
    );
    fatalIOErrorOf([&] { bodyFrom(heavy + "mass 0;"); }, {"mass"});
    fatalIOErrorOf([&] { bodyFrom(heavy + "mass -241;"); }, {"mass"});
    fatalIOErrorOf
    (
        [&] { bodyFrom(heavy + "mass 241; momentOfInertia 0;"); },
        {"momentOfInertia"}
    );
    fatalIOErrorOf
    (
        [&] { bodyFrom(heavy + "mass 241; constraints (x z);"); },
        {"constraints", "'z'", "rotation"}
    );
    fatalIOErrorOf
    (
        [&]
        {
            bodyFrom
            (
                std::string(wedge) + "motion prescribed;"
                "velocityTable ((0 (0 0 0)) (0.1 (0 1 0)) (0.1 (0 2 0)));"
            );
        },
        {"velocityTable", "increase"}
    );
    fatalIOErrorOf
    (
        [&]
        {
            bodyFrom
            (
                std::string(wedge) + "motion prescribed;"
                "velocityTable ((0.2 (0 0 0)) (0.1 (0 1 0)));"
            );
        },
        {"velocityTable"}
    );
    fatalIOErrorOf
    (
        [&] { bodyFrom(std::string(wedge) + "motion prescribed; velocityTable ();"); },
        {"velocityTable"}
    );
    fatalIOErrorOf
    (
        [&]
        {
            bodyFrom
            (
                std::string(wedge) + "motion prescribed; velocity (0 1 0);"
                "velocityTable ((0 (0 0 0)));"
            );
        },
        {"velocity", "velocityTable", "not both"}
    );
    fatalIOErrorOf
    (
        [&] { bodyFrom(std::string(wedge) + "motion prescribed;"); },
        {"velocity", "velocityTable"}
    );
}


TEST(RigidBodyDictionary, unknownKeywordsShapesAndMotionsStopNamingThem)
{
    fatalIOErrorOf
    (
        [] { bodyFrom(std::string(wedge) + "motion free; mass 1; centreOfMas (0 0 0);"); },
        {"centreOfMas", "centreOfMass"}
    );
    // A keyword of the other shape or motion model
    fatalIOErrorOf
    (
        [] { bodyFrom(std::string(wedge) + "radius 1; motion free; mass 1;"); },
        {"radius"}
    );
    fatalIOErrorOf
    (
        [] { bodyFrom(std::string(wedge) + "motion prescribed; velocity (0 0 0); mass 1;"); },
        {"mass"}
    );
    fatalIOErrorOf
    (
        [] { bodyFrom(std::string(wedge) + "motion free; mass 1; velocity (0 1 0);"); },
        {"velocity"}
    );
    fatalIOErrorOf
    (
        [] { bodyFrom("shape sphere; radius 1; motion free; mass 1;"); },
        {"shape", "sphere", "polygon", "circle"}
    );
    fatalIOErrorOf
    (
        [] { bodyFrom(std::string(wedge) + "motion floating; mass 1;"); },
        {"motion", "floating", "free", "prescribed"}
    );
}


TEST(RigidBodies, readsEveryBodyInOrderAndRejectsBadEntries)
{
    const rigidBodies bodies
    (
        dictionaryFrom
        (
            std::string("bodies {")
          + "wedge {" + wedge + "motion free; mass 241; }"
          + "cylinder { shape circle; centre (0 -1.25 0); radius 1;"
            " motion prescribed; velocity (0 0.39 0); }"
          + "}"
        )
    );
    ASSERT_EQ(bodies.size(), 2);
    EXPECT_EQ(bodies[0].name(), "wedge");
    EXPECT_EQ(bodies[0].shape().type(), "polygon");
    EXPECT_EQ(bodies[0].motion().type(), "free");
    EXPECT_EQ(bodies[1].name(), "cylinder");
    EXPECT_EQ(bodies[1].motion().type(), "prescribed");
    EXPECT_EQ(bodies.findBody("cylinder"), 1);
    EXPECT_EQ(bodies.findBody("sphere"), -1);

    EXPECT_EQ(rigidBodies(dictionaryFrom("")).size(), 0);
    EXPECT_EQ(rigidBodies(dictionaryFrom("bodies {}")).size(), 0);

    fatalIOErrorOf
    (
        [] { rigidBodies(dictionaryFrom("bodies (wedge);")); }, {"bodies"}
    );
    fatalIOErrorOf
    (
        [] { rigidBodies(dictionaryFrom("bodies { wedge polygon; }")); },
        {"wedge", "sub-dictionary"}
    );
    fatalIOErrorOf
    (
        [] { rigidBodies(dictionaryFrom("bodies {} body { }")); }, {"body"}
    );
}


TEST(RigidBodies, elementContactDistanceDefaultsToAQuarterSpacingAndIsChecked)
{
    EXPECT_EQ(rigidBodies(dictionaryFrom("")).elementContactDistance(), 0.25);
    EXPECT_EQ
    (
        rigidBodies
        (
            dictionaryFrom("elementContactDistance 0.1; bodies {}")
        ).elementContactDistance(),
        0.1
    );
    for (const char* bad : {"0", "-0.1", "0.6"})
    {
        SCOPED_TRACE(bad);
        fatalIOErrorOf
        (
            [&]
            {
                rigidBodies
                (
                    dictionaryFrom
                    (
                        std::string("elementContactDistance ") + bad + ';'
                    )
                );
            },
            {"elementContactDistance"}
        );
    }
}


TEST(RigidBodies, readsConstantRigidBodyPropertiesOfACase)
{
    namespace fs = std::filesystem;
    std::string tmpl =
        (fs::temp_directory_path()/"spemRigidBodyTest-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    const fs::path caseDir = fs::path(tmpl)/"wedgeCase";
    fs::create_directories(caseDir/"system");
    fs::create_directories(caseDir/"constant");

    const std::string header =
        "FoamFile { version 2.0; format ascii; class dictionary; object ";
    std::ofstream(caseDir/"system"/"controlDict")
        << header << "controlDict; }\n"
        << "application spemFoam; startFrom startTime; startTime 0;"
        << " stopAt endTime; endTime 1; deltaT 0.1; writeControl timeStep;"
        << " writeInterval 1;\n";

    {
        const Time runTime
        (
            Time::controlDictName,
            fileName(caseDir.parent_path().string()),
            fileName("wedgeCase")
        );
        EXPECT_EQ(rigidBodies(runTime).size(), 0);   // no file: no bodies
    }

    std::ofstream(caseDir/"constant"/"rigidBodyProperties")
        << header << "rigidBodyProperties; }\n"
        << "bodies { wedge { " << wedge
        << " motion free; mass 241; initialVelocity (0 -6.15 0);"
        << " constraints (x rotation); } }\n";
    const Time runTime
    (
        Time::controlDictName,
        fileName(caseDir.parent_path().string()),
        fileName("wedgeCase")
    );
    const rigidBodies bodies(runTime);
    ASSERT_EQ(bodies.size(), 1);
    EXPECT_EQ(bodies[0].name(), "wedge");
    EXPECT_EQ(bodies[0].velocity().y(), -6.15);

    fs::remove_all(caseDir.parent_path());
}


// * * * * * * * * * * * * * * * * * Restart * * * * * * * * * * * * * * * * //

TEST(RigidBodyRestart, writtenStateContinuesBitForBit)
{
    // Loads that depend on the state (a spring and a torsion spring), so
    // that any state not restored would show
    const std::string text =
        "bodies {"
        "  wedge { " + std::string(wedge)
      + "    motion free; mass 241; initialVelocity (0.2 -6.15 0);"
        "    initialAngularVelocity 0.5; }"
        "  cylinder { shape circle; centre (0 -1.25 0); radius 1;"
        "    motion prescribed; angularVelocity 0.3;"
        "    velocityTable ((0 (0 0 0)) (0.05 (0 0.39 0))); }"
        "}";

    auto run = [](rigidBodies& bodies, const label first, const label last)
    {
        for (label step = first; step < last; ++step)
        {
            // Steps of varying size, as a CFL limit gives
            const scalar deltaT = 1e-3*(1 + 0.3*std::sin(step));
            const scalar time = 1e-3*step;
            for (rigidBody& body : bodies)
            {
                body.advance
                (
                    time,
                    deltaT,
                    -5000*body.position().x(),
                    -3000*body.position().y(),
                    -40*body.angle(),
                    0,
                    -9.81
                );
            }
        }
    };

    rigidBodies uninterrupted(dictionaryFrom(text));
    run(uninterrupted, 0, 200);

    rigidBodies first(dictionaryFrom(text));
    run(first, 0, 97);
    dictionary state;
    first.writeState(state);

    // Through text, as a time directory holds it
    OStringStream os;
    os.precision(17);
    os << state;
    const dictionary stateRead(dictionaryFrom(os.str()));

    rigidBodies continued(dictionaryFrom(text));
    continued.readState(stateRead);
    run(continued, 97, 200);

    for (label b = 0; b < 2; ++b)
    {
        SCOPED_TRACE(uninterrupted[b].name());
        EXPECT_EQ(continued[b].position().x(), uninterrupted[b].position().x());
        EXPECT_EQ(continued[b].position().y(), uninterrupted[b].position().y());
        EXPECT_EQ(continued[b].angle(), uninterrupted[b].angle());
        EXPECT_EQ(continued[b].velocity().x(), uninterrupted[b].velocity().x());
        EXPECT_EQ(continued[b].velocity().y(), uninterrupted[b].velocity().y());
        EXPECT_EQ
        (
            continued[b].angularVelocity(), uninterrupted[b].angularVelocity()
        );
        EXPECT_EQ(continued[b].force().x(), uninterrupted[b].force().x());
        EXPECT_EQ(continued[b].moment(), uninterrupted[b].moment());
        EXPECT_NE(continued[b].position().y(), first[b].position().y());
    }

    // A body missing from the state
    dictionary partial(stateRead);
    partial.remove("cylinder");
    fatalIOErrorOf([&] { continued.readState(partial); }, {"cylinder"});
}
