/*---------------------------------------------------------------------------*\
Description
    Unit tests of the tank and the wall contact (src/SPEM/mesh/tankBoundary,
    src/SPEM/coupling/wallContact).

      - TankBoundary.*   a 1 x 0.5 m tank with an open top: which points are
                         outside it by more than the query distance (above
                         the rim is inside, beside the tank too; below the
                         rim beside the side walls is outside), the nearest
                         wall point and its normal, the sign at a corner;
                         open sides above a walled floor, an open top and
                         bottom, a boundary open all round; the distance to
                         the nearest wall beside the nearest boundary point.
      - WallContact.*    a neoHookean cantilever 0.04 m thick clamped to the
                         left wall 0.1 m above the floor, loaded by its own
                         weight with g = 100 m/s^2: unsupported its tip
                         would sag 1.5 rho g L^4/(E t^2) = 12 m (linear
                         theory), so it lands on the floor; no node ever
                         crosses it (to round-off), while the same run
                         without the contact does cross it (nor with the
                         nodes' clearances 100 times too large: measured). The same plate
                         lying on the floor lifts off it under an upward
                         load and does not sink under a downward one. A
                         heavy free cylinder and a tilted free square
                         dropped from 0.3 m never cross the floor; with
                         restitution 0 the cylinder comes to rest on it,
                         with 0.5 it leaves with half its impact speed.

\*---------------------------------------------------------------------------*/

#include "tankBoundary.H"
#include "wallContact.H"
#include "rigidBodies.H"
#include "testMeshes.H"
#include "testModels.H"
#include "IStringStream.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace Foam;

namespace
{

//- The tank of the TankBoundary tests: [0, 1] x [0, 0.5], open top
triMesh openTank()
{
    return testMeshes::build
    (
        {{0, 1, 0, 0.5, 10, 5, "water"}},
        testMeshes::split::alternating,
        [](double, double, double, double ny) -> std::string
        {
            return ny > 0.5 ? "top" : "walls";
        }
    );
}

List<patchType> openTankTypes(const triMesh& mesh)
{
    return testModels::patchTypes
    (
        mesh, {{"walls", patchType::slipWall}, {"top", patchType::freeSurface}}
    );
}

dictionary dictionaryFrom(const std::string& text)
{
    IStringStream is(text);
    return dictionary(is);
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * TankBoundary  * * * * * * * * * * * * * * //

TEST(TankBoundary, pointsFartherThanReachOutsideTheWallsAreOutside)
{
    const triMesh mesh = openTank();
    const tankBoundary tank(mesh, openTankTypes(mesh), 0.05);
    EXPECT_TRUE(tank.open());
    EXPECT_EQ(tank.nEdges(), 2*10 + 2*5);
    EXPECT_EQ(tank.nWallEdges(), 10 + 2*5);

    // Inside, and within reach outside a wall
    EXPECT_FALSE(tank.outside(0.5, 0.25));
    EXPECT_FALSE(tank.outside(0.013, 0.25));
    EXPECT_FALSE(tank.outside(-0.049, 0.25));
    EXPECT_FALSE(tank.outside(0.5, -0.049));
    EXPECT_FALSE(tank.outside(1.049, 0.01));
    // Beyond reach behind a wall
    EXPECT_TRUE(tank.outside(-0.051, 0.25));
    EXPECT_TRUE(tank.outside(0.5, -0.051));
    EXPECT_TRUE(tank.outside(1.2, 0.25));
    EXPECT_TRUE(tank.outside(0.5, -3));
    // Above the open top the tank goes on
    EXPECT_FALSE(tank.outside(0.5, 0.6));
    EXPECT_FALSE(tank.outside(0.02, 40));
    EXPECT_FALSE(tank.outside(1.04, 3));
    // Not a number is nowhere
    EXPECT_TRUE(tank.outside(std::nan(""), 0.2));
}


TEST(TankBoundary, aboveTheRimBesideTheTankIsInsideBelowItOutside)
{
    // The damBreak splash that stopped the tutorial at t = 0.698 s: 1 m
    // above the rim and 1.36 cm beside the left wall, here 0.3 m beside
    const triMesh mesh = openTank();
    const tankBoundary tank(mesh, openTankTypes(mesh), 0.05);
    EXPECT_EQ(tank.nOpenings(), 1);
    EXPECT_EQ(tank.nOpenLoops(), 0);
    EXPECT_FALSE(tank.outside(-0.0136, 1.5));
    EXPECT_FALSE(tank.outside(-0.3, 0.6));
    EXPECT_FALSE(tank.outside(1.3, 0.6));
    EXPECT_FALSE(tank.outside(-1e6, 1e6));
    // Within reach below the rim's line, beside the tank: still inside
    EXPECT_FALSE(tank.outside(-0.3, 0.451));
    // Fallen below the rim beside the tank (more than reach below it, more
    // than reach from the wall): outside
    EXPECT_TRUE(tank.outside(-0.3, 0.449));
    EXPECT_TRUE(tank.outside(1.3, 0.4));
    EXPECT_TRUE(tank.outside(-0.0136 - 0.06, 0.3));
}


TEST(TankBoundary, openSidesAboveAWalledFloorOpenOntoEverythingAboveIt)
{
    // Sides and top open, the floor a wall: one opening from the floor's
    // right end round to its left end; the open side of the line through
    // them is everything above the floor (the edges' own half-planes
    // would have covered the ground beside the tank too)
    const triMesh mesh = testMeshes::build
    (
        {{0, 1, 0, 0.5, 10, 5, "water"}},
        testMeshes::split::alternating,
        [](double, double, double, double ny) -> std::string
        {
            return ny < -0.5 ? "floor" : "open";
        }
    );
    const tankBoundary tank
    (
        mesh,
        testModels::patchTypes
        (
            mesh,
            {{"floor", patchType::slipWall}, {"open", patchType::freeSurface}}
        ),
        0.05
    );
    EXPECT_EQ(tank.nOpenings(), 1);
    EXPECT_FALSE(tank.outside(-3, 0.2));
    EXPECT_FALSE(tank.outside(4, 0.01));
    EXPECT_FALSE(tank.outside(4, 7));
    EXPECT_TRUE(tank.outside(-3, -0.06));
    EXPECT_TRUE(tank.outside(1.5, -0.2));
    EXPECT_TRUE(tank.outside(0.5, -0.2));
}


TEST(TankBoundary, openTopAndOpenBottomAreTwoOpeningsTheSidesStayWalls)
{
    // The openings of hydrostaticElasticPlate: the water's top and the
    // plate's traction-free bottom; the side walls between
    const triMesh mesh = testMeshes::build
    (
        {{0, 1, -0.1, 0.5, 10, 6, "water"}},
        testMeshes::split::alternating,
        [](double, double, double, double ny) -> std::string
        {
            return std::abs(ny) > 0.5 ? "open" : "walls";
        }
    );
    const tankBoundary tank
    (
        mesh,
        testModels::patchTypes
        (
            mesh,
            {{"walls", patchType::slipWall}, {"open", patchType::freeSurface}}
        ),
        0.05
    );
    EXPECT_EQ(tank.nOpenings(), 2);
    EXPECT_FALSE(tank.outside(0.5, 3));
    EXPECT_FALSE(tank.outside(-2, 0.6));
    EXPECT_FALSE(tank.outside(0.5, -3));
    EXPECT_TRUE(tank.outside(-2, 0.2));
    EXPECT_TRUE(tank.outside(1.2, 0.2));
}


TEST(TankBoundary, boundaryOpenAllRoundHasNothingOutside)
{
    const triMesh mesh = openTank();
    const tankBoundary tank
    (
        mesh,
        testModels::patchTypes
        (
            mesh,
            {{"walls", patchType::freeSurface}, {"top", patchType::freeSurface}}
        ),
        0.05
    );
    EXPECT_EQ(tank.nOpenings(), 0);
    EXPECT_EQ(tank.nOpenLoops(), 1);
    EXPECT_FALSE(tank.outside(-3, -4));
    EXPECT_FALSE(tank.outside(0.5, 0.25));
    EXPECT_FALSE(tank.outside(1e6, 0.25));
    EXPECT_TRUE(tank.outside(std::nan(""), 0.2));
}


TEST(TankBoundary, nearestWallPointHasTheOutwardNormalAndTheSign)
{
    const triMesh mesh = openTank();
    const tankBoundary tank(mesh, openTankTypes(mesh), 0.05);
    tankBoundary::nearestPoint q;

    // 0.01 below the floor: behind it
    ASSERT_TRUE(tank.nearest(0.33, -0.01, q));
    EXPECT_NEAR(q.signedDistance, 0.01, 1e-14);
    EXPECT_NEAR(q.x, 0.33, 1e-14);
    EXPECT_NEAR(q.y, 0, 1e-14);
    EXPECT_NEAR(q.nx, 0, 1e-14);
    EXPECT_NEAR(q.ny, -1, 1e-14);
    EXPECT_TRUE(q.wall);
    EXPECT_TRUE(tank.behindWall(0.33, -0.01, q));

    // 0.02 inside the right wall
    ASSERT_TRUE(tank.nearest(0.98, 0.27, q));
    EXPECT_NEAR(q.signedDistance, -0.02, 1e-14);
    EXPECT_NEAR(q.nx, 1, 1e-14);
    EXPECT_FALSE(tank.behindWall(0.98, 0.27, q));

    // Beyond the lower-left corner: outside, the normal from the corner
    ASSERT_TRUE(tank.nearest(-0.03, -0.04, q));
    EXPECT_NEAR(q.signedDistance, 0.05, 1e-14);
    EXPECT_NEAR(q.nx, -0.6, 1e-14);
    EXPECT_NEAR(q.ny, -0.8, 1e-14);
    // Inside near that corner
    ASSERT_TRUE(tank.nearest(0.01, 0.02, q));
    EXPECT_LT(q.signedDistance, 0);

    // Just above the open top: outside the mesh, but not behind a wall
    ASSERT_TRUE(tank.nearest(0.5, 0.51, q));
    EXPECT_GT(q.signedDistance, 0);
    EXPECT_FALSE(q.wall);
    EXPECT_FALSE(tank.behindWall(0.5, 0.51, q));

    // Deep inside: nothing within reach
    EXPECT_FALSE(tank.nearest(0.5, 0.25, q));

    // The distance to the nearest wall point beside the nearest boundary
    // point: 0.01 below the open top, 0.03 from the left wall; with no
    // wall within reach, reach
    scalar wallDistance = -1;
    ASSERT_TRUE(tank.nearest(0.03, 0.49, q, &wallDistance));
    EXPECT_FALSE(q.wall);
    EXPECT_NEAR(q.signedDistance, -0.01, 1e-14);
    EXPECT_NEAR(wallDistance, 0.03, 1e-14);
    ASSERT_TRUE(tank.nearest(0.5, 0.49, q, &wallDistance));
    EXPECT_EQ(wallDistance, tank.reach());
}


// * * * * * * * * * * * * * * * * WallContact * * * * * * * * * * * * * * * //

namespace
{

const double plateLength = 0.6, plateThickness = 0.04, gap = 0.1;
const std::string plateSolid = "model neoHookean; rho 1000; E 1e6; nu 0.3;";

//- A tank [0, 1] x [0, 0.3] of void, with a plate [0, L] x [y0, y0 + t]
//  clamped to the left wall (patch clamp); floor and sides slip walls,
//  top open
triMesh plateMesh(const double y0)
{
    const double h = 0.02, y1 = y0 + plateThickness;
    std::vector<testMeshes::block> blocks;
    if (y0 > 0)
    {
        blocks.push_back({0, 1, 0, y0, 50, int(std::lround(y0/h)), "air"});
    }
    blocks.push_back({0, plateLength, y0, y1, 30, 2, "plate"});
    blocks.push_back({plateLength, 1, y0, y1, 20, 2, "air"});
    blocks.push_back({0, 1, y1, 0.3, 50, int(std::lround((0.3 - y1)/h)), "air"});
    return testMeshes::build
    (
        blocks, testMeshes::split::alternating,
        [y0, y1](double mx, double my, double nx, double ny) -> std::string
        {
            if (nx < -0.5 && my > y0 && my < y1) return "clamp";
            return ny > 0.5 ? "top" : "walls";
        }
    );
}

std::unique_ptr<elementModel> plateModel(const triMesh& mesh)
{
    PtrList<spemMaterial> mats(mesh.nRegions());
    mats.set
    (
        mesh.findRegion("plate"), testModels::material("plate", plateSolid)
    );
    return testModels::model
    (
        mesh, std::move(mats),
        {
            {"clamp", patchType::clamped}, {"walls", patchType::slipWall},
            {"top", patchType::freeSurface}
        }
    );
}

//- Run the plate to endTime under gravity gy, with or without the wall
//  contact; the lowest y any plate node reached after a step (and its
//  contact correction) and the tip's final y
void runPlate
(
    const triMesh& mesh,
    const double y0,
    const double gy,
    const bool contact,
    const double endTime,
    double& lowest,
    double& tipY
)
{
    std::unique_ptr<elementModel> em = plateModel(mesh);
    em->setGravity(0, gy);
    em->setMassDamping(20);
    const List<patchType> types = testModels::patchTypes
    (
        mesh,
        {
            {"clamp", patchType::clamped}, {"walls", patchType::slipWall},
            {"top", patchType::freeSurface}
        }
    );
    const tankBoundary tank(mesh, types, 0.04);
    const rigidBodies noBodies(dictionaryFrom(""));
    if (contact) wallContact::releaseSolidSlipNodes(*em);
    wallContact walls(tank, em.get(), noBodies);
    ASSERT_GT(walls.nStructureNodes(), 0);

    // The node at the tip's lower corner (L, y0)
    label tip = -1;
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        const scalar* X = &mesh.points()[2*n];
        if (std::abs(X[0] - plateLength) < 1e-9 && std::abs(X[1] - y0) < 1e-9)
        {
            tip = n;
        }
    }
    ASSERT_GE(tip, 0);
    ASSERT_TRUE(em->evaluate()) << em->failure();
    lowest = GREAT;
    for (double t = 0; t < endTime; )
    {
        const double dt = 0.5*em->stableDeltaT();
        ASSERT_TRUE(em->advance(dt)) << em->failure();
        if (contact)
        {
            ASSERT_TRUE(walls.correctStructures(*em, dt)) << walls.failure();
        }
        t += dt;
        for (label k = 0; k < em->nElements(); ++k)
        {
            for (label i = 0; i < 3; ++i)
            {
                const label n = em->elementNodes()[3*k + i];
                lowest = std::min(lowest, em->positions()[2*n + 1]);
            }
        }
        ASSERT_TRUE(em->evaluate()) << em->failure();
    }
    tipY = em->positions()[2*tip + 1];
}

} // End anonymous namespace


TEST(WallContact, platePressedOnTheFloorNeverCrossesIt)
{
    const triMesh mesh = plateMesh(gap);
    double lowest, tipY, lowestFree, tipYFree;
    // Lands after sqrt(2 gap/g) = 0.045 s; 0.3 s lets it settle on the
    // floor (damping 20 1/s)
    runPlate(mesh, gap, -100, true, 0.3, lowest, tipY);
    runPlate(mesh, gap, -100, false, 0.3, lowestFree, tipYFree);
    std::cout << "plate on the floor: lowest node y " << lowest
        << " m, tip " << tipY << " m; without the contact: lowest "
        << lowestFree << " m" << std::endl;
    // On the floor to round-off of the coordinates, never below
    EXPECT_GE(lowest, -1e-12);
    // It did reach the floor (the tip rests on it)
    EXPECT_LT(tipY, 1e-3);
    // The test can fail: without the contact the plate goes through
    EXPECT_LT(lowestFree, -gap);
}


TEST(WallContact, plateRestingOnTheFloorLiftsOffAndDoesNotSink)
{
    const triMesh mesh = plateMesh(0);
    double lowest, tipY;
    // Pushed down: stays on the floor
    runPlate(mesh, 0, -100, true, 0.1, lowest, tipY);
    std::cout << "plate resting, pushed down: lowest node y " << lowest
        << " m, tip " << tipY << " m" << std::endl;
    EXPECT_GE(lowest, -1e-12);
    EXPECT_NEAR(tipY, 0, 1e-12);
    // Pulled up: the free end leaves the floor (unsupported: 12 m upward
    // in linear theory; within 0.1 s it rises by centimetres)
    runPlate(mesh, 0, 100, true, 0.1, lowest, tipY);
    std::cout << "plate resting, pulled up: tip " << tipY << " m"
        << std::endl;
    EXPECT_GT(tipY, 0.01);
}


namespace
{

//- Drop body `b` of rigidBodyProperties text on the floor of the open
//  tank under g = 9.81 for 1 s: the lowest y any of its surface points
//  reached, the velocity just before the first contact and the one after
void dropBody
(
    const std::string& bodiesText,
    const bool contact,
    double& lowest,
    double& impactSpeed,
    double& afterSpeed,
    double& finalSpeed
)
{
    const triMesh mesh = testMeshes::build
    (
        {{-1, 1, 0, 1, 40, 20, "water"}},
        testMeshes::split::alternating,
        [](double, double, double, double ny) -> std::string
        {
            return ny > 0.5 ? "top" : "walls";
        }
    );
    const tankBoundary tank(mesh, openTankTypes(mesh), 0.1);
    rigidBodies bodies(dictionaryFrom(bodiesText));
    wallContact walls(tank, nullptr, bodies);
    rigidBody& body = bodies[0];
    const double dt = 1e-4;
    lowest = GREAT;
    impactSpeed = afterSpeed = 0;
    bool touched = false;
    for (double t = 0; t < 1; t += dt)
    {
        const double vBefore = body.velocity().y();
        body.advance(t, dt, 0, 0, 0, 0, -9.81);
        if (contact)
        {
            ASSERT_TRUE(walls.correctBodies(bodies, dt)) << walls.failure();
        }
        if (!touched && walls.nBodyContacts() > 0)
        {
            touched = true;
            impactSpeed = -vBefore;
            afterSpeed = body.velocity().y();
        }
        const std::vector<scalar> P = body.surfacePoints(0.005);
        for (label i = 0; i < label(P.size()/2); ++i)
        {
            lowest = std::min(lowest, P[2*i + 1]);
        }
    }
    finalSpeed = std::hypot(body.velocity().x(), body.velocity().y());
}

} // End anonymous namespace


TEST(WallContact, heavyBodiesDroppedOnTheFloorNeverCrossIt)
{
    const std::string cylinder =
        "bodies { drop { shape circle; centre (0 0.4 0); radius 0.1;"
        " motion free; mass 5000; } }";
    double lowest, impact, after, final;
    dropBody(cylinder, true, lowest, impact, after, final);
    // Free fall from 0.3 m: sqrt(2 g 0.3) = 2.43 m/s at the floor
    std::cout << "cylinder: lowest point " << lowest << " m, impact "
        << impact << " m/s, after " << after << " m/s, at 1 s |v| "
        << final << " m/s" << std::endl;
    // The contact points of the cylinder are s = 1 % of its bounding-box
    // diagonal apart: between two of them it sinks at most s^2/(8 R)
    const double s = 0.01*std::sqrt(8.0)*0.1, sagitta = s*s/(8*0.1);
    EXPECT_GE(lowest, -sagitta);
    EXPECT_NEAR(impact, std::sqrt(2*9.81*0.3), 0.01);
    // Restitution 0 (default): it stops on the floor and stays there. The
    // contact point is up to s/2 off the centre line, so the impulse also
    // spins the disc (I = m R^2/2) and leaves at most 2 (s/2)^2/R^2 of the
    // impact speed; at rest, under g dt per step
    const double offCentre = 2*(s/2)*(s/2)/(0.1*0.1);
    EXPECT_NEAR(after, 0, offCentre*impact);
    EXPECT_LT(final, 9.81*1e-4);

    double lowestFree, impactFree, afterFree, finalFree;
    dropBody(cylinder, false, lowestFree, impactFree, afterFree, finalFree);
    std::cout << "cylinder without the contact: lowest point " << lowestFree
        << " m" << std::endl;
    EXPECT_LT(lowestFree, -1);

    // Restitution 0.5: it leaves with half its impact speed
    std::string bouncing = cylinder;
    bouncing.replace(bouncing.find("mass"), 4, "wallRestitution 0.5; mass");
    dropBody(bouncing, true, lowest, impact, after, final);
    std::cout << "cylinder, restitution 0.5: impact " << impact
        << " m/s, after " << after << " m/s" << std::endl;
    EXPECT_GE(lowest, -sagitta);
    EXPECT_NEAR(after/impact, 0.5, offCentre);

    // A square turned by 30 degrees lands on a corner and tips over
    const double c = std::cos(M_PI/6), sn = std::sin(M_PI/6), a = 0.1;
    std::ostringstream square;
    square << "bodies { box { shape polygon; points (";
    for (const std::pair<double, double>& p :
        {std::make_pair(-a, -a), {a, -a}, {a, a}, {-a, a}})
    {
        square << '(' << c*p.first - sn*p.second << ' '
            << 0.45 + sn*p.first + c*p.second << " 0) ";
    }
    square << "); motion free; mass 4000; } }";
    dropBody(square.str(), true, lowest, impact, after, final);
    std::cout << "tilted square: lowest point " << lowest << " m, at 1 s |v| "
        << final << " m/s" << std::endl;
    EXPECT_GE(lowest, -1e-12);
}


// ************************************************************************* //
