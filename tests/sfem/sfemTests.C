/*---------------------------------------------------------------------------*\
Description
    Unit tests of the element half (ES-FEM, paper sect. 2.1): the patch
    test on an irregular mesh, lumped masses, a conversion undone after a
    failed step, the stable time step of a deformed solid, and the stress
    of each constitutive model for a known deformation, in plane strain
    and plane stress, with its tangent wave speed.

\*---------------------------------------------------------------------------*/

#include "testMeshes.H"
#include "testModels.H"
#include "testDictionaries.H"
#include "elasticSolid.H"
#include "initialDensity.H"
#include "IStringStream.H"

#include <gtest/gtest.h>
#include <algorithm>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace Foam;

namespace
{

const std::string plateSolid = "model linearElastic; rho 2700; E 67.5e9; nu 0.34;";

//- An irregular single-region mesh: 8 x 6 cells on [0,1] x [0,0.75] with
//  interior nodes moved by up to 30 % of the spacing
triMesh irregularMesh(const std::string& region)
{
    return testMeshes::perturbed
    (
        testMeshes::build({{0, 1, 0, 0.75, 8, 6, region}}), 0.3, 0.125
    );
}

//- A linear field w = G x + b at every node (2 per node)
std::vector<scalar> linearField
(
    const std::vector<scalar>& x, const scalar G[4], const scalar b[2]
)
{
    std::vector<scalar> w(x.size());
    for (size_t n = 0; n < x.size()/2; ++n)
    {
        w[2*n] = G[0]*x[2*n] + G[1]*x[2*n + 1] + b[0];
        w[2*n + 1] = G[2]*x[2*n] + G[3]*x[2*n + 1] + b[1];
    }
    return w;
}

//- Nodes on no boundary segment
std::vector<bool> interiorNodes(const triMesh& mesh)
{
    std::vector<bool> interior(mesh.nPoints(), true);
    for (label v : mesh.segments()) interior[v] = false;
    return interior;
}

} // End anonymous namespace


TEST(ESFEM, patchTestReproducesLinearVelocityFieldInFluid)
{
    const triMesh mesh = irregularMesh("water");
    auto em = testModels::model(mesh, {{"water", testModels::water}});

    // A uniformly compressed configuration (uniform pressure) moving with a
    // linear velocity field (uniform viscous stress), gradients taken on
    // the current configuration
    const scalar F[4] = {-2e-3, 5e-4, 0, -1e-3};   // x = X + F X
    const scalar zero[2] = {0, 0};
    std::vector<scalar> x = linearField(mesh.points(), F, zero);
    for (size_t i = 0; i < x.size(); ++i) x[i] += mesh.points()[i];
    const scalar G[4] = {0.3, -1.7, 2.2, -0.3};
    const scalar b[2] = {0.5, -4.0};
    em->setState(x, linearField(x, G, b));
    ASSERT_TRUE(em->evaluate());

    const std::vector<scalar>& g = em->domainGradient();
    for (label k = 0; k < em->nDomains(); ++k)
    {
        for (label i = 0; i < 4; ++i)
        {
            ASSERT_NEAR(g[4*k + i], G[i], 1e-12) << "domain " << k;
        }
    }

    // Uniform pressure rho0 c^2 (1/J - 1) in every domain (eq. 7)
    const scalar J = (1 + F[0])*(1 + F[3]) - F[1]*F[2];
    const scalar p = 100*100*1000*(1/J - 1);
    std::vector<scalar> sigma(6*em->nDomains()), pk(em->nDomains());
    em->domainCauchyStress(0, em->nDomains(), sigma.data(), pk.data());
    for (label k = 0; k < em->nDomains(); ++k)
    {
        ASSERT_NEAR(pk[k], p, 1e-9*p) << "domain " << k;
    }

    // A uniform stress is in equilibrium at every interior node
    const std::vector<scalar> f = em->nodalForces();
    const std::vector<bool> interior = interiorNodes(mesh);
    const scalar scale = p*0.125;   // |sigma| times the spacing
    int nInterior = 0;
    scalar boundaryMax = 0;
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        if (!interior[n])
        {
            boundaryMax = std::max(boundaryMax, std::hypot(f[2*n], f[2*n + 1]));
            continue;
        }
        ++nInterior;
        EXPECT_NEAR(f[2*n], 0, 1e-10*scale) << "node " << n;
        EXPECT_NEAR(f[2*n + 1], 0, 1e-10*scale) << "node " << n;
    }
    EXPECT_GT(nInterior, 20);
    EXPECT_GT(boundaryMax, 0.1*scale);
}


TEST(ESFEM, patchTestReproducesLinearDisplacementFieldInSolid)
{
    const triMesh mesh = irregularMesh("plate");
    auto em = testModels::model(mesh, {{"plate", plateSolid}});

    const scalar H[4] = {1e-3, 2e-4, -5e-4, -3e-4};   // displacement gradient
    const scalar c[2] = {1e-3, 2e-3};
    std::vector<scalar> u = linearField(mesh.points(), H, c);
    std::vector<scalar> x(mesh.points());
    for (size_t i = 0; i < x.size(); ++i) x[i] += u[i];
    em->setState(x, std::vector<scalar>(x.size(), 0));
    ASSERT_TRUE(em->evaluate());

    const std::vector<scalar>& g = em->domainGradient();
    for (label k = 0; k < em->nDomains(); ++k)
    {
        for (label i = 0; i < 4; ++i)
        {
            ASSERT_NEAR(g[4*k + i], H[i], 1e-12) << "domain " << k;
        }
    }

    // Uniform stress: zero force at interior nodes, nonzero on the boundary
    const std::vector<scalar> f = em->nodalForces();
    const std::vector<bool> interior = interiorNodes(mesh);
    const scalar scale = 67.5e9*1e-3*0.125;
    scalar boundaryMax = 0;
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        if (interior[n])
        {
            EXPECT_NEAR(f[2*n], 0, 1e-11*scale) << "node " << n;
            EXPECT_NEAR(f[2*n + 1], 0, 1e-11*scale) << "node " << n;
        }
        else
        {
            boundaryMax = std::max(boundaryMax, std::hypot(f[2*n], f[2*n + 1]));
        }
    }
    EXPECT_GT(boundaryMax, 1e-3*scale);
}


TEST(ESFEM, nodalMassesSumToRegionMasses)
{
    // Water on a plate: a conforming two-region mesh
    const triMesh mesh = testMeshes::build
    ({
        {0, 1, -0.1, 0, 10, 2, "plate"},
        {0, 1, 0, 0.6, 10, 12, "water"}
    });
    auto em = testModels::model
    (
        mesh, {{"water", testModels::water}, {"plate", plateSolid}}
    );

    const scalar waterMass = 1000*0.6, plateMass = 2700*0.1;
    scalar nodeSum = 0;
    for (scalar m : em->nodeMass())
    {
        ASSERT_GT(m, 0);
        nodeSum += m;
    }
    EXPECT_NEAR(nodeSum, waterMass + plateMass, 1e-12*(waterMass + plateMass));

    // The domain masses of each region sum to the region mass
    for (const elementModel::region& r : em->regions())
    {
        scalar sum = 0;
        for (label k = r.domainBegin; k < r.domainEnd; ++k)
        {
            sum += em->domainMass()[k];
        }
        const scalar expected = r.name == "water" ? waterMass : plateMass;
        EXPECT_NEAR(sum, expected, 1e-12*expected) << r.name;
    }

    // Interface edges give one domain per side: 10 extra domains
    EXPECT_EQ(em->nDomains(), mesh.nEdges() + 10);
}


// removeTriangles() renumbers the elements and domains left from the
// numbering before (removeRemovedElements(), removeRemovedNodeElements());
// restoreTriangles() builds them from the mesh. The same removed set must
// give the same model, bit for bit. Triangles taken out in four
// conversions, among them first and second elements of domains and a
// whole node's
void expectRemovalGivesTheBuildsModel
(
    const triMesh& mesh,
    const std::map<std::string, std::string>& materials,
    const label node,
    const std::vector<label>& alsoFirst
)
{
    auto removed = testModels::model(mesh, materials);
    auto built = testModels::model(mesh, materials);

    // Every third triangle; then those of the node and alsoFirst; then
    // every fifth of the rest, and every seventh of what is left (four
    // rounds: a fault that cycles with the three corners of an element
    // does not cancel out)
    std::vector<std::vector<label>> rounds(4);
    std::vector<bool> out(mesh.nTriangles(), false);
    for (label t = 0; t < mesh.nTriangles(); t += 3) rounds[0].push_back(t);
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        for (label a = 0; a < 3; ++a)
        {
            if (mesh.triangles()[3*t + a] == node && t % 3) rounds[1].push_back(t);
        }
    }
    for (const label t : alsoFirst) rounds[1].push_back(t);
    for (const auto& round : {rounds[0], rounds[1]})
    {
        for (const label t : round) out[t] = true;
    }
    // Every n-th of the triangles not taken out yet
    const auto everyNthLeft = [&](const label n, std::vector<label>& round)
    {
        for (label t = 0, k = 0; t < mesh.nTriangles(); ++t)
        {
            if (!out[t] && ++k % n == 0) round.push_back(t);
        }
        for (const label t : round) out[t] = true;
    };
    everyNthLeft(5, rounds[2]);
    everyNthLeft(7, rounds[3]);

    std::vector<label> all;
    for (const auto& round : rounds)
    {
        removed->removeTriangles(mesh, round);
        all.insert(all.end(), round.begin(), round.end());
    }
    // The reference: the same set, and one triangle more put back, which
    // builds it from the mesh
    label extra = 0;
    while (std::find(all.begin(), all.end(), extra) != all.end()) ++extra;
    all.push_back(extra);
    built->removeTriangles(mesh, all);
    built->restoreTriangles(mesh, {extra});

    ASSERT_EQ(removed->nElements(), built->nElements());
    EXPECT_EQ(removed->elementTriangle(), built->elementTriangle());
    EXPECT_EQ(removed->elementNodes(), built->elementNodes());
    EXPECT_EQ(removed->elementDomains(), built->elementDomains());
    EXPECT_EQ(removed->domainElements(), built->domainElements());
    EXPECT_EQ(removed->nodeElementStart(), built->nodeElementStart());
    EXPECT_EQ(removed->nodeElements(), built->nodeElements());
    EXPECT_EQ(removed->elementMass(), built->elementMass());
    EXPECT_EQ(removed->elementArea(), built->elementArea());
    EXPECT_EQ(removed->nodeMass(), built->nodeMass());
    EXPECT_EQ(removed->domainMass(), built->domainMass());
    EXPECT_EQ(removed->domainArea(), built->domainArea());
    for (label n = 0; n < removed->nNodes(); ++n)
    {
        EXPECT_EQ(removed->solidNode(n), built->solidNode(n)) << "node " << n;
    }
    ASSERT_EQ(removed->regions().size(), built->regions().size());
    forAll(removed->regions(), r)
    {
        const elementModel::region& a = removed->regions()[r];
        const elementModel::region& b = built->regions()[r];
        EXPECT_EQ(a.elemBegin, b.elemBegin) << a.name;
        EXPECT_EQ(a.elemEnd, b.elemEnd) << a.name;
        EXPECT_EQ(a.domainBegin, b.domainBegin) << a.name;
        EXPECT_EQ(a.domainEnd, b.domainEnd) << a.name;
    }
    ASSERT_TRUE(removed->evaluate());
    ASSERT_TRUE(built->evaluate());
    EXPECT_EQ(removed->nodalForces(), built->nodalForces());
}


TEST(ESFEM, removingTrianglesNumbersTheRestAsABuildFromTheMeshDoes)
{
    // A plate under water (domains across the interface; the solid
    // partition built again), node 40's triangles and two of the plate's
    const triMesh mesh = testMeshes::build
    ({
        {0, 1, -0.1, 0, 10, 2, "plate"},
        {0, 1, 0, 0.6, 10, 12, "water"}
    });
    expectRemovalGivesTheBuildsModel
    (
        mesh, {{"water", testModels::water}, {"plate", plateSolid}}, 40,
        {1, 5}
    );
}


TEST(ESFEM, removingTrianglesOfAModelWithoutSolidsNumbersTheRestAsABuildDoes)
{
    // Water alone (buildSolidPartition()'s way without a solid region)
    const triMesh mesh = testMeshes::build({{0, 1, 0, 0.6, 10, 12, "water"}});
    expectRemovalGivesTheBuildsModel
    (
        mesh, {{"water", testModels::water}}, 40, {1, 5}
    );
}


TEST(ESFEM, restoreTrianglesAfterARevertGivesBackTheModelBeforeTheRemoval)
{
    // A step that converts the elements round a corner node (leaving it
    // without elements) and fails: revert() and restoreTriangles() give
    // the model of the step before, bit for bit, the corner's velocity too
    const triMesh mesh = testMeshes::build({{0, 1, 0, 0.5, 6, 3, "water"}});
    auto em = testModels::model(mesh, {{"water", testModels::water}});
    const scalar G[4] = {0.1, 0.3, -0.2, 0.05}, b[2] = {0.4, -0.1};
    em->setVelocity(linearField(mesh.points(), G, b));
    ASSERT_TRUE(em->evaluate());
    ASSERT_TRUE(em->advance(1e-4));
    ASSERT_TRUE(em->evaluate());

    // What the model is and holds before the failing step
    const std::vector<label> triangle = em->elementTriangle();
    const std::vector<label> nodes = em->elementNodes();
    const std::vector<label> domains = em->elementDomains();
    const std::vector<label> nodeElements = em->nodeElements();
    const std::vector<scalar> elementMass = em->elementMass();
    const std::vector<scalar> nodeMass = em->nodeMass();
    const std::vector<scalar> domainMass = em->domainMass();
    const std::vector<scalar> domainArea = em->domainArea();
    const std::vector<scalar> x = em->positions();
    const std::vector<scalar> v = em->velocities();
    const std::vector<scalar> f = em->nodalForces();

    // The triangles of node 0 (a corner)
    std::vector<label> corner;
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        for (label a = 0; a < 3; ++a)
        {
            if (mesh.triangles()[3*t + a] == 0) corner.push_back(t);
        }
    }
    ASSERT_FALSE(corner.empty());
    ASSERT_NE(v[0], 0);

    ASSERT_TRUE(em->advance(1e-4));
    em->removeTriangles(mesh, corner);
    EXPECT_EQ(em->nodeMass()[0], 0);
    EXPECT_EQ(em->velocities()[0], 0);
    EXPECT_EQ(em->nElements(), label(triangle.size() - corner.size()));
    em->revert();
    em->restoreTriangles(mesh, corner);
    ASSERT_TRUE(em->evaluate());

    EXPECT_EQ(em->elementTriangle(), triangle);
    EXPECT_EQ(em->elementNodes(), nodes);
    EXPECT_EQ(em->elementDomains(), domains);
    EXPECT_EQ(em->nodeElements(), nodeElements);
    EXPECT_EQ(em->elementMass(), elementMass);
    EXPECT_EQ(em->nodeMass(), nodeMass);
    EXPECT_EQ(em->domainMass(), domainMass);
    EXPECT_EQ(em->domainArea(), domainArea);
    EXPECT_EQ(em->positions(), x);
    EXPECT_EQ(em->velocities(), v);
    EXPECT_EQ(em->nodalForces(), f);
    for (const label t : corner) EXPECT_FALSE(em->removed(t));
}


TEST(ESFEM, locateFindsWhatAPassOverEveryElementFindsWhileTheMeshMovesAndConverts)
{
    // locate() in the current configuration uses a grid (elementLocator)
    // kept while the nodes move by under half an element: the element it
    // returns must be the one the pass over every element in index order
    // returns (the lowest-numbered that contains the point), at points
    // inside, on edges and nodes, and outside, as the mesh shears and
    // loses triangles; and the grid must be reused between small moves
    const triMesh mesh = testMeshes::build({{0, 1, 0, 0.5, 12, 6, "water"}});
    auto em = testModels::model(mesh, {{"water", testModels::water}});
    const scalar G[4] = {0.4, 1.5, -0.3, -0.4}, b[2] = {0.2, -0.1};
    em->setVelocity(linearField(mesh.points(), G, b));

    const auto bruteForce =
        [&](const scalar px, const scalar py, scalar bary[3])
        {
            for (label el = 0; el < em->nElements(); ++el)
            {
                if
                (
                    elementLocator::contains
                    (
                        em->positions(), &em->elementNodes()[3*el], px, py,
                        bary
                    )
                )
                {
                    return el;
                }
            }
            return label(-1);
        };
    // Points: a regular lattice over and beyond the mesh, and every node
    // and edge midpoint of the current configuration
    const auto check = [&](const char* when)
    {
        SCOPED_TRACE(when);
        std::vector<scalar> pts;
        for (label i = -3; i <= 53; ++i)
        {
            for (label j = -3; j <= 28; ++j)
            {
                pts.push_back(0.0213*i - 0.01);
                pts.push_back(0.0197*j - 0.01);
            }
        }
        const std::vector<scalar>& x = em->positions();
        for (label el = 0; el < em->nElements(); ++el)
        {
            const label* n = &em->elementNodes()[3*el];
            for (label a = 0; a < 3; ++a)
            {
                const label c = n[(a + 1) % 3];
                pts.push_back(x[2*n[a]]);
                pts.push_back(x[2*n[a] + 1]);
                pts.push_back(0.5*(x[2*n[a]] + x[2*c]));
                pts.push_back(0.5*(x[2*n[a] + 1] + x[2*c + 1]));
            }
        }
        // All points in one call first (a probe set), which checks the
        // grid once, so that it is the one to find a stale grid
        std::vector<label> batch;
        std::vector<scalar> batchBary;
        em->locate(pts, batch, batchBary);
        ASSERT_EQ(batch.size(), pts.size()/2);
        label inside = 0;
        for (std::size_t k = 0; k < pts.size()/2; ++k)
        {
            scalar w[3] = {0, 0, 0}, wb[3] = {0, 0, 0};
            const label el = em->locate(pts[2*k], pts[2*k + 1], false, w);
            const label elb = bruteForce(pts[2*k], pts[2*k + 1], wb);
            ASSERT_EQ(el, elb) << "point " << pts[2*k] << ' ' << pts[2*k + 1];
            ASSERT_EQ(batch[k], elb) << "point " << pts[2*k] << ' ' << pts[2*k + 1];
            if (el >= 0)
            {
                ++inside;
                for (label a = 0; a < 3; ++a)
                {
                    EXPECT_EQ(w[a], wb[a]);
                    EXPECT_EQ(batchBary[3*k + a], wb[a]);
                }
            }
        }
        EXPECT_GT(inside, 100);

        // elementsNear (setGhosts' search, on the same grid): in
        // increasing order, each once, and every element with a point of
        // its triangle in the rectangle among them (the points tried: its
        // nodes, centroid and the midpoints between them). The last entry
        // is two rectangles at once: their union
        const std::vector<std::vector<scalar>> rects =
        {
            {0.3, 0.1, 0.5, 0.2}, {0.0, 0.0, 1.0, 0.5},
            {0.61, -0.2, 0.62, 0.9}, {2.0, 2.0, 3.0, 3.0},
            {-0.5, 0.24, 1.5, 0.26},
            {0.1, 0.05, 0.12, 0.4, 0.8, 0.3, 0.95, 0.33}
        };
        for (const std::vector<scalar>& R : rects)
        {
            std::vector<label> near;
            ASSERT_TRUE(em->elementsNear(R, near));
            for (std::size_t k = 1; k < near.size(); ++k)
            {
                ASSERT_LT(near[k - 1], near[k]) << "not increasing, or twice";
            }
            label needed = 0;
            for (label el = 0; el < em->nElements(); ++el)
            {
                const label* n = &em->elementNodes()[3*el];
                const scalar cx =
                    (x[2*n[0]] + x[2*n[1]] + x[2*n[2]])/3;
                const scalar cy =
                    (x[2*n[0] + 1] + x[2*n[1] + 1] + x[2*n[2] + 1])/3;
                const auto inside = [&](const scalar px, const scalar py)
                {
                    for (std::size_t r = 0; r < R.size(); r += 4)
                    {
                        if
                        (
                            R[r] <= px && px <= R[r + 2]
                         && R[r + 1] <= py && py <= R[r + 3]
                        )
                        {
                            return true;
                        }
                    }
                    return false;
                };
                bool in = inside(cx, cy);
                for (label a = 0; a < 3; ++a)
                {
                    for (const scalar w : {0.0, 0.5})
                    {
                        in = in
                         || inside
                            (
                                (1 - w)*x[2*n[a]] + w*cx,
                                (1 - w)*x[2*n[a] + 1] + w*cy
                            );
                    }
                }
                if (!in) continue;
                ++needed;
                EXPECT_TRUE(std::binary_search(near.begin(), near.end(), el))
                    << "element " << el << " missing for the rectangle ("
                    << R[0] << ' ' << R[1] << ") (" << R[2] << ' ' << R[3]
                    << ')' << (R.size() > 4 ? " and another" : "");
            }
            if (R[0] > 1.5)
            {
                EXPECT_TRUE(near.empty()) << "elements far beyond the mesh";
            }
            if (R.size() == 4 && R[2] - R[0] < 0.05)
            {
                EXPECT_LT(label(near.size()), em->nElements()/2)
                    << "a thin strip lists half the elements";
                EXPECT_GT(needed, 0);
            }
        }
    };

    ASSERT_TRUE(em->evaluate());
    check("at the start");
    // Small steps: the grid is rebuilt only when a node has moved by 0.9
    // of half an element (0.9 x 0.5 x sqrt(1/288) = 0.0265 m); the
    // speeds are up to about 1.35 m/s
    const scalar dt = 0.5*em->stableDeltaT();
    const label builds0 = em->locatorBuilds();
    scalar t = 0;
    while (t < 0.005)
    {
        ASSERT_TRUE(em->advance(dt));
        ASSERT_TRUE(em->evaluate());
        t += dt;
        scalar w[3];
        em->locate(0.5, 0.25, false, w);
    }
    EXPECT_EQ(em->locatorBuilds(), builds0) << "rebuilt after small moves";
    check("after 5 mm");
    // Checked every 2.5 ms, so that grids up to their limit (0.5 to 0.9 of
    // the margin moved) are asked too, not only fresh ones
    for (label k = 1; k <= 40; ++k)
    {
        while (t < 0.005 + 0.0025*k)
        {
            ASSERT_TRUE(em->advance(dt));
            ASSERT_TRUE(em->evaluate());
            t += dt;
        }
        check("while shearing");
    }
    EXPECT_GT(em->locatorBuilds(), builds0 + 2) << "not rebuilt while moving";
    // Elements taken out (conversion): the grid must not keep them
    std::vector<label> some, others;
    for (label tri = 0; tri < mesh.nTriangles(); tri += 3)
    {
        some.push_back(tri);
        others.push_back(tri + 1);
    }
    // (the grid of the last check, renumbered: no build)
    const label buildsBeforeRemoval = em->locatorBuilds();
    em->removeTriangles(mesh, some);
    check("after removing a third of the triangles");
    EXPECT_EQ(em->locatorBuilds(), buildsBeforeRemoval)
        << "built again after a removal";
    // Put back and as many others out, with no query between: the same
    // element count, other elements (the topology version, not the count,
    // must tell the grid)
    em->restoreTriangles(mesh, some);
    em->removeTriangles(mesh, others);
    check("after removing as many others");
}


TEST(ESFEM, locateFollowsEveryWayTheNodesMove)
{
    // The grid is checked once per change of the positions (not once per
    // query): each way the element model moves its nodes must count as a
    // change. Each mover below shifts the whole mesh by 0.3 m in x after a
    // query made the grid; a point beyond the old mesh but inside the new
    // one must then be found, and one that only the old mesh covered not
    const triMesh mesh = testMeshes::build({{0, 1, 0, 0.5, 8, 4, "water"}});
    auto em = testModels::model(mesh, {{"water", testModels::water}});
    const scalar shift = 0.3;
    const auto shifted = [&](const std::vector<scalar>& x)
    {
        std::vector<scalar> y(x);
        for (std::size_t n = 0; n < y.size()/2; ++n) y[2*n] += shift;
        return y;
    };
    const auto expectShifted = [&](const std::string& how)
    {
        scalar w[3];
        const scalar x0 = em->positions()[0] - shift;   // node 0 before
        EXPECT_GE(em->locate(x0 + 1.15, 0.25, false, w), 0)
            << how << ": a point of the moved mesh not found";
        EXPECT_EQ(em->locate(x0 + 0.1, 0.25, false, w), -1)
            << how << ": a point the mesh left still found";
    };
    scalar w[3];
    const auto query = [&]() { em->locate(0.5, 0.25, false, w); };

    query();
    em->setState(shifted(em->positions()), em->velocities());
    expectShifted("setState");

    query();
    {
        const std::vector<scalar> x = shifted(em->positions());
        for (label n = 0; n < em->nNodes(); ++n)
        {
            em->setPosition(n, x[2*n], x[2*n + 1]);
        }
    }
    expectShifted("setPosition");

    query();
    for (label n = 0; n < em->nNodes(); ++n)
    {
        em->correctVelocity(n, shift/1e-3, 0, 1e-3);
    }
    expectShifted("correctVelocity");

    // A step that moves the mesh by 0.3 m, then revert(): the grid of the
    // moved mesh must not serve the reverted one
    {
        std::vector<scalar> v(em->velocities().size(), 0);
        for (std::size_t n = 0; n < v.size()/2; ++n) v[2*n] = -shift/1e-3;
        em->setState(em->positions(), v);
    }
    ASSERT_TRUE(em->evaluate());
    ASSERT_TRUE(em->advance(1e-3));
    query();
    em->revert();
    expectShifted("revert");
}


TEST(ESFEM, locatorSkipsItsPassOnlyWhileTheBoundHoldsEveryNodesMove)
{
    // The grid's pass over the nodes is skipped while a bound on the moves
    // since it was built (the last pass's drift plus dt max|v| per step
    // and the move of each interface correction) stays within its reach.
    // The bound must hold each node's true move since the build, at every
    // check, and it must skip most passes in a smooth flow. The mesh and
    // shear of locateFindsWhatAPassOverEveryElementFinds...: speeds up to
    // about 1.35 m/s, a reach of 0.0265 m
    const triMesh mesh = testMeshes::build({{0, 1, 0, 0.5, 24, 12, "water"}});
    auto em = testModels::model(mesh, {{"water", testModels::water}});
    const scalar G[4] = {0.4, 1.5, -0.3, -0.4}, b[2] = {0.2, -0.1};
    em->setVelocity(linearField(mesh.points(), G, b));
    ASSERT_TRUE(em->evaluate());
    const scalar dt = 0.5*em->stableDeltaT();

    std::vector<scalar> built;      // the positions of the last build
    label builds = -1, checks = 0;
    scalar tightest = std::numeric_limits<scalar>::max();
    scalar w[3];
    for (label step = 0; step < 600; ++step)
    {
        ASSERT_TRUE(em->advance(dt));
        ASSERT_TRUE(em->evaluate());
        // Interface corrections (eq. 26) of a few nodes, every third step,
        // up to 0.5 m/s
        if (step % 3 == 0)
        {
            for (label k = 0; k < 4; ++k)
            {
                const label n = (37*step + 101*k) % em->nNodes();
                em->correctVelocity
                (
                    n, 0.5*std::sin(step + k), 0.5*std::cos(3*step + k), dt
                );
            }
        }
        em->locate(0.5, 0.25, false, w);
        ++checks;
        if (em->locatorBuilds() != builds)
        {
            builds = em->locatorBuilds();
            built = em->positions();
        }
        const std::vector<scalar>& x = em->positions();
        scalar moved = 0;
        for (std::size_t i = 0; i < x.size(); ++i)
        {
            moved = std::max(moved, std::abs(x[i] - built[i]));
        }
        const scalar bound = em->locatorDriftBound();
        ASSERT_LE(moved, bound) << "step " << step;
        if (moved > 0.01) tightest = std::min(tightest, bound/moved);
    }
    EXPECT_GT(em->locatorBuilds(), 3) << "the mesh did not move enough";
    EXPECT_LT(em->locatorPasses(), checks/4)
        << "passes not skipped: " << em->locatorPasses() << " of " << checks;
    std::printf
    (
        "%d checks, %d passes, %d builds; the bound at least %.3f times the"
        " largest move (moves above 0.01 m)\n",
        int(checks), int(em->locatorPasses()), int(em->locatorBuilds()),
        tightest
    );
}


TEST(ESFEM, stableStepOfACompressedNeoHookeanBlockComesFromItsCurrentState)
{
    // A unit block of 4 x 4 cells (right triangles of legs 0.25), squeezed
    // to 70 % of its height by prescribed positions: the shortest altitude,
    // that onto the hypotenuse, shrinks and the neo-Hookean stiffens
    // (rho0 c^2 = lambda (1 - ln J) + mu (1 + l_max^2), l_max = 1 here)
    const scalar E = 2e6, nu = 0.3, rho = 1000, squeeze = 0.7, dx = 0.25;
    const scalar lambda = E*nu/((1 + nu)*(1 - 2*nu)), mu = E/(2*(1 + nu));
    const triMesh mesh = testMeshes::build({{0, 1, 0, 1, 4, 4, "block"}});
    std::vector<scalar> squeezed(mesh.points());
    for (size_t n = 0; n < squeezed.size()/2; ++n) squeezed[2*n + 1] *= squeeze;
    const std::vector<scalar> rest(squeezed.size(), 0);

    const auto altitude = [](const scalar a, const scalar b)
    {
        return a*b/std::hypot(a, b);
    };
    const scalar cRest = std::sqrt((lambda + 2*mu)/rho);
    const scalar cSqueezed =
        std::sqrt((lambda*(1 - std::log(squeeze)) + 2*mu)/rho);
    const scalar dtRest = altitude(dx, dx)/cRest;
    const scalar dtSqueezed = altitude(dx, squeeze*dx)/cSqueezed;

    auto nh = testModels::model
    (
        mesh, {{"block", "model neoHookean; rho 1000; E 2e6; nu 0.3;"}}
    );
    ASSERT_TRUE(nh->evaluate());
    // At rest as before: the reference altitude over waveSpeed()
    EXPECT_DOUBLE_EQ(nh->stableDeltaT(), dtRest);
    EXPECT_DOUBLE_EQ(nh->stableDeltaT(), altitude(dx, dx)/nh->material(0).waveSpeed());
    nh->setState(squeezed, rest);
    ASSERT_TRUE(nh->evaluate()) << nh->failure();
    EXPECT_NEAR(nh->stableDeltaT(), dtSqueezed, 1e-14*dtSqueezed);
    EXPECT_LT(nh->stableDeltaT(), dtRest);
    std::printf
    (
        "neo-Hookean block squeezed to %.0f %%: stable step %.6e s, at rest"
        " %.6e s (ratio %.4f: altitude %.4f, wave speed %.4f)\n",
        100*squeeze, nh->stableDeltaT(), dtRest, nh->stableDeltaT()/dtRest,
        altitude(dx, squeeze*dx)/altitude(dx, dx), cSqueezed/cRest
    );

    // linearElastic: its stiffness is that of the reference configuration
    // whatever the state, and so is its step
    auto lin = testModels::model
    (
        mesh, {{"block", "model linearElastic; rho 1000; E 2e6; nu 0.3;"}}
    );
    ASSERT_TRUE(lin->evaluate());
    EXPECT_DOUBLE_EQ(lin->stableDeltaT(), dtRest);
    lin->setState(squeezed, rest);
    ASSERT_TRUE(lin->evaluate());
    EXPECT_DOUBLE_EQ(lin->stableDeltaT(), dtRest);
}


TEST(ESFEM, invertedHyperelasticElementStopsTheStep)
{
    // One node pushed through the opposite edge of its element: the step
    // would come from a negative area
    const triMesh mesh = testMeshes::build({{0, 1, 0, 1, 2, 2, "block"}});
    auto em = testModels::model
    (
        mesh, {{"block", "model neoHookean; rho 1000; E 2e6; nu 0.3;"}}
    );
    std::vector<scalar> x(mesh.points());
    // The corner node (0, 0) of the first element moved across it
    x[0] = 0.8;
    x[1] = 0.8;
    em->setState(x, std::vector<scalar>(x.size(), 0));
    EXPECT_FALSE(em->evaluate());
    EXPECT_NE
    (
        em->failure().find("an element of solid region block is inverted"),
        std::string::npos
    ) << em->failure();
}


// * * * * * * * * * * * * * * * Initial state  * * * * * * * * * * * * * * //

namespace
{

// Water 0.5 m wide and 0.6 m deep under 0.4 m of empty space (void)
const triMesh tankWithAir()
{
    return testMeshes::build
    ({
        {0, 0.5, 0, 0.6, 5, 12, "water"},
        {0, 0.5, 0.6, 1.0, 5, 8, "air"}
    });
}

const std::string hydrostaticWater =
    "model weaklyCompressibleNewtonian; rho 1000; c 20; initialPressure hydrostatic;";

//- initialDensity on the mesh with the region dictionaries given as text
std::vector<scalar> densityOf
(
    const triMesh& mesh,
    const std::string& regionsText,
    const std::map<std::string, patchType>& patches,
    const scalar gx,
    const scalar gy
)
{
    IStringStream is(regionsText);
    const dictionary regions(is);
    PtrList<spemMaterial> mats(mesh.nRegions());
    forAll(mesh.regionNames(), r)
    {
        const dictionary& d = regions.subDict(mesh.regionNames()[r]);
        if (d.get<word>("model") != "void")
        {
            mats.set(r, spemMaterial::New(mesh.regionNames()[r], d));
        }
    }
    return initialDensity
    (
        mesh, testModels::patchTypes(mesh, patches), mats, regions, gx, gy
    );
}

scalar centroidY(const triMesh& mesh, const label t)
{
    const label* n = &mesh.triangles()[3*t];
    return
    (
        mesh.points()[2*n[0] + 1] + mesh.points()[2*n[1] + 1]
      + mesh.points()[2*n[2] + 1]
    )/3;
}

} // End anonymous namespace


TEST(InitialDensity, hydrostaticWaterIsTheExactWeaklyCompressibleColumnBelowTheVoid)
{
    const triMesh mesh = tankWithAir();
    const std::vector<scalar> rho = densityOf
    (
        mesh,
        "water {" + hydrostaticWater + "} air { model void; }",
        {{"left", patchType::slipWall}, {"right", patchType::slipWall},
         {"bottom", patchType::slipWall}},
        0, -9.81
    );
    ASSERT_EQ(label(rho.size()), mesh.nTriangles());
    const label water = mesh.findRegion("water");
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        if (mesh.triangleRegion()[t] != water)
        {
            EXPECT_EQ(rho[t], 0) << "void triangle " << t;
            continue;
        }
        // The free surface is the water-void interface at y = 0.6:
        // dp/dz = -rho g with p = c^2 (rho - rho0)
        const scalar depth = 0.6 - centroidY(mesh, t);
        const scalar exact = 1000*std::exp(9.81*depth/(20*20));
        EXPECT_NEAR(rho[t], exact, 1e-12*exact) << "triangle " << t;
    }
}


TEST(InitialDensity, freeSurfacePatchSetsTheLevelAndZeroStartKeepsRho0)
{
    // Water only: its top patch is the free surface at y = 1
    const triMesh mesh = testMeshes::build({{0, 0.5, 0, 1.0, 5, 20, "water"}});
    const auto walls = std::map<std::string, patchType>
    {
        {"left", patchType::noSlipWall}, {"right", patchType::noSlipWall},
        {"bottom", patchType::noSlipWall}
    };
    const std::vector<scalar> hydro = densityOf
    (
        mesh, "water {" + hydrostaticWater + "}", walls, 0, -9.81
    );
    const std::vector<scalar> zero = densityOf
    (
        mesh, "water { model weaklyCompressibleNewtonian; rho 1000; c 20; }",
        walls, 0, -9.81
    );
    scalar pBottomRow = 0;
    label nBottomRow = 0;
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        EXPECT_EQ(zero[t], 1000);
        const scalar y = centroidY(mesh, t);
        const scalar exact = 1000*std::exp(9.81*(1 - y)/400);
        EXPECT_NEAR(hydro[t], exact, 1e-12*exact);
        if (y < 0.05)
        {
            pBottomRow += 400*(hydro[t] - 1000) - 1000*9.81*(1 - y);
            ++nBottomRow;
        }
    }
    // Against rho0 g d the weakly compressible column is heavier by
    // g d/(2 c^2) = 1.2 % at the bottom: not the linear profile
    ASSERT_GT(nBottomRow, 0);
    EXPECT_GT(pBottomRow/nBottomRow, 0.01*1000*9.81*0.97);
}


TEST(InitialDensity, hydrostaticRegionWithoutFreeSurfaceStopsNamingTheRegion)
{
    const triMesh mesh = testMeshes::build({{0, 1, 0, 1, 4, 4, "water"}});
    const bool wasThrowing = FatalIOError.throwExceptions();
    std::string message;
    try
    {
        densityOf
        (
            mesh, "water {" + hydrostaticWater + "}",
            {{"left", patchType::noSlipWall}, {"right", patchType::noSlipWall},
             {"bottom", patchType::noSlipWall}, {"top", patchType::noSlipWall}},
            0, -9.81
        );
        ADD_FAILURE() << "a closed hydrostatic region was accepted";
    }
    catch (const IOerror& err)
    {
        message = err.message();
    }
    FatalIOError.throwExceptions(wasThrowing);
    std::cout << "FatalIOError message:\n" << message << std::endl;
    EXPECT_NE(message.find("water"), std::string::npos) << message;
    EXPECT_NE(message.find("free surface"), std::string::npos) << message;
}


namespace
{

//- Largest node speed over 0.4 s (two periods of the first acoustic mode,
//  4 H/c = 0.2 s) of an undamped water column 0.5 x 1 m of nx x 2 nx
//  cells, started at p = 0 or hydrostatic
scalar largestSpeedOfColumn(const int nx, const bool hydrostatic)
{
    const triMesh mesh =
        testMeshes::build({{0, 0.5, 0, 1.0, nx, 2*nx, "water"}});
    const auto walls = std::map<std::string, patchType>
    {
        {"left", patchType::slipWall}, {"right", patchType::slipWall},
        {"bottom", patchType::slipWall}
    };
    const std::string text =
        "model weaklyCompressibleNewtonian; rho 1000; c 20; mu 1e-3;"
      + std::string(hydrostatic ? " initialPressure hydrostatic;" : "");
    const std::vector<scalar> rho =
        densityOf(mesh, "water {" + text + "}", walls, 0, -9.81);
    auto em = testModels::model
    (
        mesh, testModels::materials(mesh, {{"water", text}}), walls, rho
    );
    em->setGravity(0, -9.81);
    EXPECT_TRUE(em->evaluate()) << em->failure();
    scalar t = 0, vMax = 0;
    while (t < 0.4)
    {
        const scalar dt = 0.5*em->stableDeltaT();
        if (!em->advance(dt) || !em->evaluate())
        {
            ADD_FAILURE() << em->failure();
            break;
        }
        t += dt;
        for (label n = 0; n < em->nNodes(); ++n)
        {
            const scalar* v = &em->velocities()[2*n];
            vMax = std::max(vMax, std::hypot(v[0], v[1]));
        }
    }
    return vMax;
}

} // End anonymous namespace


TEST(InitialDensity, hydrostaticStartKeepsAnElementColumnAtRest)
{
    // Without damping, a column started at p = 0 falls under gravity for
    // the acoustic time H/c and then oscillates with a velocity of order
    // g H/c. Started hydrostatic it is in equilibrium up to the
    // discretisation: the residual motion shrinks with the cell size.
    const scalar zero = largestSpeedOfColumn(10, false);
    const scalar coarse = largestSpeedOfColumn(5, true);
    const scalar fine = largestSpeedOfColumn(10, true);
    const scalar finer = largestSpeedOfColumn(20, true);
    std::printf
    (
        "largest node speed over 0.4 s: started at p = 0 %.3e m/s (g H/c ="
        " %.3e); hydrostatic %.3e, %.3e, %.3e m/s at 5, 10, 20 cells wide\n",
        zero, 9.81*1.0/20, coarse, fine, finer
    );
    EXPECT_GT(zero, 0.5*9.81*1.0/20);
    EXPECT_LT(fine, 0.02*zero);
    // At least first order in the cell size
    EXPECT_LT(fine, 0.6*coarse);
    EXPECT_LT(finer, 0.6*fine);
}


// * * * * * * * * * * * * * * * Materials  * * * * * * * * * * * * * * * * //

namespace
{

struct stressResult
{
    scalar P[4];        // force stress (Cauchy or first Piola-Kirchhoff)
    scalar sigma[6];    // Cauchy xx yy zz xy yz xz
    scalar p;
    bool ok;
};

stressResult stressOf
(
    const spemMaterial& m, const scalar g[4], scalar area = 1, scalar mass = 0
)
{
    stressResult r;
    r.ok = m.stress(0, 1, g, &area, &mass, r.P);
    m.cauchyStress(0, 1, g, &area, &mass, r.sigma, &r.p);
    return r;
}

const std::string solidDict(const std::string& model)
{
    return "model " + model + "; rho 1000; E 2e6; nu 0.3;";
}

} // End anonymous namespace


TEST(Materials, linearElasticGivesPlaneStrainStressOfUniaxialStrain)
{
    auto m = testModels::material("s", solidDict("linearElastic"));
    const scalar E = 2e6, nu = 0.3;
    const scalar lambda = E*nu/((1 + nu)*(1 - 2*nu)), mu = E/(2*(1 + nu));
    const scalar eps = 1e-3;
    const scalar g[4] = {eps, 0, 0, 0};
    const stressResult r = stressOf(m(), g);
    EXPECT_NEAR(r.P[0], (lambda + 2*mu)*eps, 1e-9*E);
    EXPECT_NEAR(r.P[3], lambda*eps, 1e-9*E);
    EXPECT_NEAR(r.sigma[2], lambda*eps, 1e-9*E);   // plane strain sigma_zz
    EXPECT_NEAR(r.P[1], 0, 1e-9*E);

    // Pure shear strain gamma: tau = mu gamma
    const scalar gs[4] = {0, 2e-3, 0, 0};
    EXPECT_NEAR(stressOf(m(), gs).P[1], mu*2e-3, 1e-9*E);

    const scalar c = std::sqrt((lambda + 2*mu)/1000);
    EXPECT_NEAR(m->waveSpeed(), c, 1e-12*c);
}


TEST(Materials, hyperelasticSolidsAreStressFreeUnderRigidRotation)
{
    for (const std::string model : {"saintVenantKirchhoff", "neoHookean"})
    {
        auto m = testModels::material("s", solidDict(model));
        const scalar a = 0.9;   // 52 degrees
        // F = R: displacement gradient R - I
        const scalar g[4] = {std::cos(a) - 1, -std::sin(a), std::sin(a), std::cos(a) - 1};
        const stressResult r = stressOf(m(), g);
        EXPECT_TRUE(r.ok);
        for (label i = 0; i < 4; ++i) EXPECT_NEAR(r.P[i], 0, 1e-9) << model;

        // linearElastic is not (small-strain theory): a sanity check that
        // the test would catch a small-strain model
        if (model == "saintVenantKirchhoff")
        {
            auto lin = testModels::material("s", solidDict("linearElastic"));
            EXPECT_GT(std::abs(stressOf(lin(), g).P[0]), 1e3);
        }
    }
}


TEST(Materials, hyperelasticSolidsGiveKnownStressOfUniaxialStretch)
{
    const scalar E = 2e6, nu = 0.3;
    const scalar lambda = E*nu/((1 + nu)*(1 - 2*nu)), mu = E/(2*(1 + nu));
    const scalar s = 1.1;   // stretch
    const scalar g[4] = {s - 1, 0, 0, 0};

    // St. Venant-Kirchhoff: E_xx = (s^2 - 1)/2, S = lambda trE I + 2 mu E,
    // P = F S, sigma = F S F^T / J
    {
        auto m = testModels::material("s", solidDict("saintVenantKirchhoff"));
        const scalar Exx = 0.5*(s*s - 1);
        const scalar Sxx = (lambda + 2*mu)*Exx, Syy = lambda*Exx;
        const stressResult r = stressOf(m(), g);
        EXPECT_NEAR(r.P[0], s*Sxx, 1e-9*E);
        EXPECT_NEAR(r.P[3], Syy, 1e-9*E);
        EXPECT_NEAR(r.sigma[0], s*Sxx, 1e-9*E);        // s^2 Sxx / s
        EXPECT_NEAR(r.sigma[1], Syy/s, 1e-9*E);
    }
    // neo-Hookean: P = mu (F - F^-T) + lambda ln J F^-T
    {
        auto m = testModels::material("s", solidDict("neoHookean"));
        const stressResult r = stressOf(m(), g);
        EXPECT_NEAR(r.P[0], mu*(s - 1/s) + lambda*std::log(s)/s, 1e-9*E);
        EXPECT_NEAR(r.P[3], lambda*std::log(s), 1e-9*E);
        EXPECT_NEAR(r.sigma[2], lambda*std::log(s)/s, 1e-9*E);
    }
}


TEST(Materials, hyperelasticSolidsReportInvertedDomains)
{
    const scalar g[4] = {-1.5, 0, 0, 0};   // J = -0.5
    for (const std::string model : {"saintVenantKirchhoff", "neoHookean"})
    {
        auto m = testModels::material("s", solidDict(model));
        EXPECT_FALSE(stressOf(m(), g).ok) << model;
    }
}


namespace
{

const std::string planeStressDict(const std::string& model)
{
    return solidDict(model) + " hypothesis planeStress;";
}

//- The lateral stretch l of a 3D neo-Hookean bar under uniaxial stress at
//  axial stretch s (l = lambda_yy = lambda_zz, P_yy = 0):
//      mu (l^2 - 1) + lambda ln(s l^2) = 0,
//  by bisection (increasing in l), independent of the model's Newton
scalar neoHookeanUniaxialLateralStretch
(
    const scalar s, const scalar lambda, const scalar mu
)
{
    scalar lo = 0.1, hi = 2;
    for (int it = 0; it < 200 && hi - lo > 1e-16; ++it)
    {
        const scalar l = 0.5*(lo + hi);
        (mu*(l*l - 1) + lambda*std::log(s*l*l) > 0 ? hi : lo) = l;
    }
    return 0.5*(lo + hi);
}

} // End anonymous namespace


TEST(Materials, planeStressLinearElasticGivesYoungsModulusUnderUniaxialStress)
{
    // Plane stress, lateral contraction -nu eps free: sigma_xx = E eps,
    // sigma_yy = sigma_zz = 0 (with E/(1 - nu^2) in place of E plane
    // strain would give sigma_xx = E eps/(1 - nu^2) at eps_yy = 0)
    const scalar E = 2e6, nu = 0.3, rho = 1000;
    auto m = testModels::material("s", planeStressDict("linearElastic"));
    const scalar eps = 1e-3;
    const scalar g[4] = {eps, 0, 0, -nu*eps};
    const stressResult r = stressOf(m(), g);
    EXPECT_NEAR(r.P[0], E*eps, 1e-9*E);
    EXPECT_NEAR(r.P[3], 0, 1e-9*E);
    EXPECT_NEAR(r.sigma[0], E*eps, 1e-9*E);
    EXPECT_NEAR(r.sigma[1], 0, 1e-9*E);
    EXPECT_EQ(r.sigma[2], 0);

    // In-plane biaxial strain: sigma = E/(1 - nu) eps, eps_zz =
    // -2 nu/(1 - nu) eps (the density sees it)
    const scalar gb[4] = {eps, 0, 0, eps};
    EXPECT_NEAR(stressOf(m(), gb).P[0], E/(1 - nu)*eps, 1e-9*E);
    scalar area = 1, mass = 0, density = 0;
    m->density(0, 1, gb, &area, &mass, &density);
    EXPECT_NEAR(density, rho*(1 - 2*eps + 2*nu/(1 - nu)*eps), 1e-12*rho);

    // Shear is the same in either hypothesis
    const scalar gs[4] = {0, 2e-3, 0, 0};
    EXPECT_NEAR(stressOf(m(), gs).P[1], E/(2*(1 + nu))*2e-3, 1e-9*E);

    // The plate's dilatational speed
    const scalar c = std::sqrt(E/(rho*(1 - nu*nu)));
    EXPECT_NEAR(m->waveSpeed(), c, 1e-12*c);
}


TEST(Materials, planeStressSaintVenantKirchhoffGivesYoungsModulusUnderUniaxialStress)
{
    // S linear in E: with E_yy = -nu E_xx free, S_xx = E E_xx, S_yy = 0
    // at any stretch; the thickness stretch equals the lateral one
    const scalar E = 2e6, nu = 0.3, rho = 1000;
    auto m = testModels::material("s", planeStressDict("saintVenantKirchhoff"));
    const scalar s = 1.1;
    const scalar Exx = 0.5*(s*s - 1), l = std::sqrt(1 - 2*nu*Exx);
    const scalar g[4] = {s - 1, 0, 0, l - 1};
    const stressResult r = stressOf(m(), g);
    EXPECT_TRUE(r.ok);
    EXPECT_NEAR(r.P[0], s*E*Exx, 1e-9*E);
    EXPECT_NEAR(r.P[3], 0, 1e-9*E);
    // Cauchy: s^2 S_xx/J_3D, J_3D = s l^2
    EXPECT_NEAR(r.sigma[0], s*s*E*Exx/(s*l*l), 1e-9*E);
    EXPECT_NEAR(r.sigma[1], 0, 1e-9*E);
    EXPECT_EQ(r.sigma[2], 0);
    scalar area = 1, mass = 0, density = 0;
    m->density(0, 1, g, &area, &mass, &density);
    EXPECT_NEAR(density, rho/(s*l*l), 1e-12*rho);

    const scalar c = std::sqrt(E/(rho*(1 - nu*nu)));
    EXPECT_NEAR(m->waveSpeed(), c, 1e-12*c);
}


TEST(Materials, planeStressNeoHookeanHasNoOutOfPlaneStress)
{
    const scalar E = 2e6, nu = 0.3, rho = 1000;
    const scalar lambda = E*nu/((1 + nu)*(1 - 2*nu)), mu = E/(2*(1 + nu));
    auto m = testModels::material("s", planeStressDict("neoHookean"));

    // Uniaxial stress at stretch 1.1 and 0.7: the lateral stretch of the
    // 3D bar (bisection above) is also the thickness stretch, so the
    // in-plane P_yy vanishes only if the model found lambda_zz = l
    for (const scalar s : {1.1, 0.7})
    {
        const scalar l = neoHookeanUniaxialLateralStretch(s, lambda, mu);
        const scalar g[4] = {s - 1, 0, 0, l - 1};
        const stressResult r = stressOf(m(), g);
        const scalar lnJ3 = std::log(s*l*l);
        EXPECT_TRUE(r.ok);
        EXPECT_NEAR(r.P[0], mu*(s - 1/s) + lambda*lnJ3/s, 1e-9*E) << s;
        EXPECT_NEAR(r.P[3], 0, 1e-9*E) << s;
        EXPECT_NEAR(r.sigma[1], 0, 1e-9*E) << s;
        EXPECT_NEAR(r.sigma[2], 0, 1e-9*E) << s;
        scalar area = 1, mass = 0, density = 0;
        m->density(0, 1, g, &area, &mass, &density);
        EXPECT_NEAR(density, rho/(s*l*l), 1e-12*rho) << s;
    }

    // A general large in-plane deformation (stretch, shear, rotation, J
    // from 0.3 to 2.2): sigma_zz, computed from the stretch the model
    // solved for, is zero to round-off
    const scalar gs[][4] =
    {
        {0.4, 0.3, -0.2, -0.3}, {-0.5, 0.2, 0.1, -0.35}, {0.6, -0.4, 0.5, 0.3}
    };
    scalar largestZZ = 0;
    for (const auto& g : gs)
    {
        const stressResult r = stressOf(m(), g);
        EXPECT_TRUE(r.ok);
        EXPECT_NEAR(r.sigma[2], 0, 1e-14*E) << g[0];
        largestZZ = std::max(largestZZ, std::abs(r.sigma[2]));
    }
    std::printf
    (
        "plane-stress neo-Hookean, large in-plane strains: |sigma_zz| <= %.2e E\n",
        largestZZ/E
    );

    const scalar c = std::sqrt(E/(rho*(1 - nu*nu)));
    EXPECT_NEAR(m->waveSpeed(), c, 1e-12*c);
}


TEST(Materials, planeStressNeoHookeanTendsToLinearElasticityAtSmallStrain)
{
    // The difference is of second order in the strain: at the amplitude
    // a it is below E a^2 (the nonlinear terms of P are of order E |g|^2;
    // measured 0.62 E a^2) and falls 100 times when a falls 10 times
    auto nh = testModels::material("s", planeStressDict("neoHookean"));
    auto lin = testModels::material("s", planeStressDict("linearElastic"));
    const scalar E = 2e6;
    const scalar shape[4] = {1, 0.4, -0.7, -0.3};
    scalar previous = 0;
    for (const scalar a : {1e-4, 1e-5})
    {
        const scalar g[4] = {a*shape[0], a*shape[1], a*shape[2], a*shape[3]};
        const stressResult rn = stressOf(nh(), g), rl = stressOf(lin(), g);
        scalar difference = 0;
        for (label i = 0; i < 4; ++i)
        {
            difference = std::max(difference, std::abs(rn.P[i] - rl.P[i]));
        }
        std::printf
        (
            "plane-stress neo-Hookean - linear elastic at strain %.0e:"
            " |P difference| = %.3e E a^2\n", a, difference/(E*a*a)
        );
        EXPECT_LT(difference, E*a*a) << a;
        if (previous > 0)
        {
            EXPECT_NEAR(previous/difference, 100, 1);
        }
        previous = difference;
    }
}


namespace
{

//- The longitudinal wave speed along x and y of the material at the
//  diagonal F = diag(lx, ly) from the tangent of its own stress:
//  rho0 c^2 = l_i^2 dP_ii/dF_ii (the current speed is l_i times the
//  reference one), by central differences, the larger of the two
scalar finiteDifferenceWaveSpeed
(
    const spemMaterial& m, const scalar lx, const scalar ly
)
{
    const scalar step = 1e-6;
    scalar modulus = 0;
    for (label i : {0, 3})
    {
        scalar gp[4] = {lx - 1, 0, 0, ly - 1}, gm[4] = {lx - 1, 0, 0, ly - 1};
        gp[i] += step;
        gm[i] -= step;
        const scalar l = i == 0 ? lx : ly;
        const scalar dPdF =
            (stressOf(m, gp).P[i] - stressOf(m, gm).P[i])/(2*step);
        modulus = std::max(modulus, l*l*dPdF);
    }
    return std::sqrt(modulus/m.rho());
}

} // End anonymous namespace


TEST(Materials, tangentWaveSpeedIsTheLongitudinalSpeedOfTheTangentStiffness)
{
    // Squeezed, stretched, and squeezed one way while stretched the other;
    // each also turned by 0.7 rad (the speed is frame invariant)
    const scalar E = 2e6, nu = 0.3;
    const scalar lambda = E*nu/((1 + nu)*(1 - 2*nu)), mu = E/(2*(1 + nu));
    const scalar stretches[][2] = {{1, 0.7}, {1.2, 1.1}, {0.8, 1.3}};
    const scalar a = 0.7, ca = std::cos(a), sa = std::sin(a);
    for (const std::string model : {"saintVenantKirchhoff", "neoHookean"})
    {
        for (const bool planeStress : {false, true})
        {
            auto m = testModels::material
            (
                "s", planeStress ? planeStressDict(model) : solidDict(model)
            );
            const std::string what =
                model + (planeStress ? " plane stress" : " plane strain");
            const scalar I[4] = {1, 0, 0, 1};
            EXPECT_NEAR
            (
                m->tangentWaveSpeed(I), m->waveSpeed(), 1e-15*m->waveSpeed()
            ) << what;
            EXPECT_FALSE(m->isGeometricallyLinear()) << what;

            for (const auto& l : stretches)
            {
                const scalar F[4] = {l[0], 0, 0, l[1]};
                const scalar RF[4] = {ca*l[0], -sa*l[1], sa*l[0], ca*l[1]};
                const scalar c = m->tangentWaveSpeed(F);
                const scalar exact = finiteDifferenceWaveSpeed(m(), l[0], l[1]);
                EXPECT_NEAR(m->tangentWaveSpeed(RF), c, 1e-14*c) << what;
                std::printf
                (
                    "%s at stretches (%.1f, %.1f): tangent wave speed %.6f"
                    " m/s, from the stress tangent %.6f m/s (%+.1e)\n",
                    what.c_str(), l[0], l[1], c, exact, c/exact - 1
                );
                if (model == "neoHookean" && planeStress)
                {
                    // The small-strain thickness log-stretch s0 bounds the
                    // real one from above: the estimate is safe, and off
                    // by second order in s0 (below s0^2; measured about
                    // s0^2/4: +0.64 % at (1, 0.7))
                    const scalar s0 =
                        -lambda*std::log(l[0]*l[1])/(lambda + 2*mu);
                    EXPECT_GE(c, exact*(1 - 1e-8)) << what;
                    EXPECT_LT(c, exact*(1 + s0*s0)) << what;
                }
                else
                {
                    // Differences of step 1e-6: truncation and round-off
                    // below 1e-8
                    EXPECT_NEAR(c, exact, 1e-8*exact) << what;
                }
            }
        }
    }

    // linearElastic: one stiffness, the reference one
    auto lin = testModels::material("s", solidDict("linearElastic"));
    EXPECT_TRUE(lin->isGeometricallyLinear());
    const scalar F[4] = {1, 0, 0, 0.7};
    EXPECT_EQ(lin->tangentWaveSpeed(F), lin->waveSpeed());
}


TEST(Materials, badHypothesisStopsNamingTheKeyword)
{
    for (const std::string value : {"planeStres", "3", "(planeStress)", "planeStress planeStrain"})
    {
        testDictionaries::fatalIOErrorOf
        (
            [&]
            {
                testModels::material
                (
                    "plate", solidDict("neoHookean") + " hypothesis " + value + ";"
                );
            },
            {"'hypothesis'", "plate", "planeStrain", "planeStress"}
        );
    }
    // Every solid model knows the keyword
    for (const std::string model : {"linearElastic", "saintVenantKirchhoff", "neoHookean"})
    {
        EXPECT_TRUE
        (
            testModels::material("plate", planeStressDict(model)).valid()
        ) << model;
    }
}


TEST(Materials, weaklyCompressibleFluidGivesStateEquationPressureAndViscousStress)
{
    auto m = testModels::material("w", testModels::water);
    // A domain of mass 1000 kg/m^3 x 1 m^2 compressed to 0.99 m^2 (eq. 7)
    const scalar g0[4] = {0, 0, 0, 0};
    const scalar rho = 1000/0.99;
    const stressResult r = stressOf(m(), g0, 0.99, 1000);
    EXPECT_NEAR(r.p, 100*100*(rho - 1000), 1e-9*r.p);
    EXPECT_NEAR(r.P[0], -r.p, 1e-9*r.p);
    EXPECT_NEAR(r.P[3], -r.p, 1e-9*r.p);

    // Simple shear dv_x/dy = 10 1/s: tau_xy = mu * 10 (eqs. 9-10)
    const scalar gs[4] = {0, 10, 0, 0};
    const stressResult s = stressOf(m(), gs, 1, 1000);
    EXPECT_NEAR(s.P[1], 1e-3*10, 1e-15);
    EXPECT_NEAR(s.P[2], 1e-3*10, 1e-15);
    EXPECT_NEAR(s.p, 0, 1e-9);

    // Expansion div v = 3: deviatoric part only (eq. 9, 3D deviator)
    const scalar ge[4] = {3, 0, 0, 0};
    const stressResult e = stressOf(m(), ge, 1, 1000);
    EXPECT_NEAR(e.P[0], 2e-3*(3 - 1), 1e-15);
    EXPECT_NEAR(e.P[3], 2e-3*(0 - 1), 1e-15);
}


TEST(Materials, bulkViscosityAddsIsotropicStressOfTheRateOfCompression)
{
    // sigma += b1 rho0 c l div(v) I with l = sqrt(1.5 A): in compression
    // it adds to the pressure the stress carries, in expansion it takes
    // from it; the thermodynamic pressure (eq. 7) and the shear are left
    // alone; the step factor is sqrt(1 + xi^2) - xi
    const scalar b1 = 0.2, rho0 = 1000, c = 100, mu = 1e-3;
    auto m = testModels::material
    (
        "w", testModels::water + " bulkViscosity 0.2;"
    );
    auto plain = testModels::material("w", testModels::water);
    const scalar A = 0.99, mass = 1000;
    const scalar p = c*c*(mass/A - rho0);
    for (const scalar div : {-3.0, 2.0})
    {
        SCOPED_TRACE("div v " + std::to_string(div));
        const scalar g[4] = {div/3, 0.5, -0.25, 2*div/3};
        const stressResult r = stressOf(m(), g, A, mass);
        const stressResult r0 = stressOf(plain(), g, A, mass);
        const scalar q = b1*rho0*c*std::sqrt(1.5*A)*div;
        for (const label i : {0, 3})
        {
            EXPECT_NEAR(r.P[i], r0.P[i] + q, 1e-12*std::abs(p));
            EXPECT_NEAR(r.P[i], -p + q + 2*mu*(g[i] - div/3), 1e-12*std::abs(p));
        }
        EXPECT_EQ(r.P[1], r0.P[1]);
        EXPECT_EQ(r.P[2], r0.P[2]);
        EXPECT_EQ(r.p, r0.p);
        EXPECT_NEAR(r.sigma[0], r0.sigma[0] + q, 1e-12*std::abs(p));
        EXPECT_NEAR(r.sigma[2], r0.sigma[2] + q, 1e-12*std::abs(p));
    }
    EXPECT_EQ(m->bulkViscosity(), b1);
    EXPECT_EQ(plain->bulkViscosity(), 0);
    EXPECT_NEAR
    (
        spemMaterial::dampedStepFactor(b1), std::sqrt(1 + b1*b1) - b1, 1e-15
    );
}


TEST(Materials, bulkViscosityOutsideZeroToOneStopsNamingTheKeyword)
{
    const bool wasThrowing = FatalIOError.throwExceptions();
    for (const std::string value : {"-0.1", "1.5"})
    {
        std::string message;
        try
        {
            testModels::material
            (
                "w", testModels::water + " bulkViscosity " + value + ";"
            );
            ADD_FAILURE() << "bulkViscosity " << value << " accepted";
        }
        catch (const IOerror& err)
        {
            message = err.message();
        }
        EXPECT_NE(message.find("bulkViscosity"), std::string::npos) << message;
        EXPECT_NE(message.find("out of range"), std::string::npos) << message;
    }
    FatalIOError.throwExceptions(wasThrowing);
}


TEST(PatchConditions, fluidNodesSlideOnANoSlipWallHeldByItsShear)
{
    // A solid block and a water block side by side on a no-slip floor,
    // cells 0.25 x 0.25 (the wall triangles' height over the floor h = l)
    const Foam::triMesh mesh = testMeshes::build
    (
        {
            {0, 0.5, 0, 0.5, 2, 2, "plate"},
            {0.5, 1.5, 0, 0.5, 4, 2, "water"}
        }
    );
    const scalar mu = 2e-3;
    std::vector<scalar> viscosity(mesh.nTriangles());
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        const bool water =
            mesh.regionNames()[mesh.triangleRegion()[t]] == "water";
        viscosity[t] = water ? mu : -1;
    }
    std::vector<elementModel::constraint> c;
    std::vector<scalar> normal, friction;
    nodeConstraints
    (
        mesh,
        testModels::patchTypes(mesh, {{"bottom", patchType::noSlipWall}}),
        10, c, normal, &viscosity, &friction
    );
    label nSlide = 0;
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        const scalar x = mesh.points()[2*n], y = mesh.points()[2*n + 1];
        if (y > 1e-12)
        {
            EXPECT_EQ(c[n], elementModel::constraint::free);
            EXPECT_EQ(friction[n], 0);
            continue;
        }
        if (x < 0.5 + 1e-12)
        {
            // Nodes of the solid, and the one it shares with the water
            EXPECT_EQ(c[n], elementModel::constraint::fixed) << "x = " << x;
            EXPECT_EQ(friction[n], 0);
            continue;
        }
        ++nSlide;
        EXPECT_EQ(c[n], elementModel::constraint::slip) << "x = " << x;
        EXPECT_NEAR(normal[2*n], 0, 1e-15);
        EXPECT_NEAR(normal[2*n + 1], -1, 1e-15);
        // mu l/h from each wall side: two, one at the floor's end
        const scalar sides = x > 1.5 - 1e-12 ? 1 : 2;
        EXPECT_NEAR(friction[n], sides*mu, 1e-15) << "x = " << x;
    }
    EXPECT_EQ(nSlide, 4);

    // Without viscosities the floor pins every node, as before
    nodeConstraints
    (
        mesh,
        testModels::patchTypes(mesh, {{"bottom", patchType::noSlipWall}}),
        10, c, normal
    );
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        if (mesh.points()[2*n + 1] < 1e-12)
        {
            EXPECT_EQ(c[n], elementModel::constraint::fixed);
        }
    }
}


// ************************************************************************* //
