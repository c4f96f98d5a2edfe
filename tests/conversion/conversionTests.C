/*---------------------------------------------------------------------------*\
Description
    Unit tests of the conversion criteria and preset particle regions, each
    on single triangles or points with a hand-computed answer:
      - minInteriorAngle (the paper's MIA, sect. 2.3) flags a triangle
        whose smallest angle is 29 deg but not 31 deg at the default 30
        deg, wherever the small corner is, accepts equilateral and
        right-isosceles triangles, flags inverted, collapsed and NaN ones,
        and rejects limits outside (0, 60);
      - stretchRatio is 1 for rotations and uniform scalings of any
        reference triangle, equals the analytic ratio of a simple shear
        F = [[1, s], [0, 1]] and flags it just above the limit but not just
        below, whatever the reference shape; reflections are flagged;
      - the selection reads `criterion` with its minInteriorAngle default,
        ignores the conversion dictionary's other keywords and rejects
        unknown names, listing the valid ones;
      - box, circle and polygon (a non-convex L, both orientations) contain
        and exclude chosen points; patchDistance on a 4 x 4 mesh selects the
        points within d of its patches only; unknown keywords, patches and
        types and bad values stop with a FatalIOError naming them.

\*---------------------------------------------------------------------------*/

#include "distortionCriterion.H"
#include "parallelLoop.H"
#include "minInteriorAngle.H"
#include "stretchRatio.H"
#include "presetParticleRegion.H"
#include "patchDistanceRegion.H"
#include "rigidBodies.H"
#include "dictionary.H"
#include "IStringStream.H"
#include "OStringStream.H"
#include "unitConversion.H"
#include "testMeshes.H"

#include "testDictionaries.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <random>
#include <string>

using namespace Foam;

namespace
{

using testDictionaries::dictionaryFrom;
using testDictionaries::fatalIOErrorOf;

//- A triangle: three (x, y) nodes
using triangle = std::array<std::array<scalar, 2>, 3>;

//- The triangle with the nodes shifted cyclically by k (same orientation)
triangle rotated(const triangle& t, const int k)
{
    return {t[k % 3], t[(k + 1) % 3], t[(k + 2) % 3]};
}

//- Isosceles triangle with apex angle apexDeg at node 0, counter-clockwise,
//  rotated by turnDeg and moved by (dx, dy): the two other angles are
//  (180 - apexDeg)/2
triangle isosceles
(
    const scalar apexDeg,
    const scalar turnDeg = 0,
    const scalar dx = 0,
    const scalar dy = 0
)
{
    const scalar a = degToRad(apexDeg), t = degToRad(turnDeg);
    return
    {{
        {dx, dy},
        {dx + std::cos(t), dy + std::sin(t)},
        {dx + std::cos(t + a), dy + std::sin(t + a)}
    }};
}

//- distorted() of the criterion for the current triangle x (and the
//  reference X, the same by default)
bool distorted
(
    const distortionCriterion& criterion,
    const triangle& x,
    const triangle* X = nullptr
)
{
    const triangle& ref = X ? *X : x;
    return criterion.distorted
    (
        x[0].data(), x[1].data(), x[2].data(),
        ref[0].data(), ref[1].data(), ref[2].data()
    );
}

//- The triangle X mapped by x = F X + (tx, ty), F row-major
triangle mapped
(
    const triangle& X,
    const std::array<scalar, 4>& F,
    const scalar tx = 0,
    const scalar ty = 0
)
{
    triangle x;
    for (int i = 0; i < 3; ++i)
    {
        x[i][0] = F[0]*X[i][0] + F[1]*X[i][1] + tx;
        x[i][1] = F[2]*X[i][0] + F[3]*X[i][1] + ty;
    }
    return x;
}

//- Row-major product A B of 2x2 matrices
std::array<scalar, 4> product
(
    const std::array<scalar, 4>& A,
    const std::array<scalar, 4>& B
)
{
    return
    {
        A[0]*B[0] + A[1]*B[2], A[0]*B[1] + A[1]*B[3],
        A[2]*B[0] + A[3]*B[2], A[2]*B[1] + A[3]*B[3]
    };
}

//- Rotation by angleDeg
std::array<scalar, 4> rotation(const scalar angleDeg)
{
    const scalar c = std::cos(degToRad(angleDeg));
    const scalar s = std::sin(degToRad(angleDeg));
    return {c, -s, s, c};
}

//- Simple shear F = [[1, s], [0, 1]] whose principal stretch ratio is
//  ratio: sigma_max/sigma_min = rho  <=>  s = sqrt(rho) - 1/sqrt(rho)
//  (rho + 1/rho = |F|^2/det F = 2 + s^2)
std::array<scalar, 4> simpleShearWithRatio(const scalar ratio)
{
    return {1, std::sqrt(ratio) - 1/std::sqrt(ratio), 0, 1};
}

//- Principal stretch ratio of the map from X to x
scalar principalStretchRatio(const triangle& x, const triangle& X)
{
    return stretchRatio::principalStretchRatio
    (
        x[0].data(), x[1].data(), x[2].data(),
        X[0].data(), X[1].data(), X[2].data()
    );
}

//- Reference triangles of different quality: equilateral, right
//  isosceles, a 15 deg sliver, an obtuse one, clockwise-free (all
//  counter-clockwise) and away from the origin
const triangle referenceTriangles[] =
{
    isosceles(60, 0, 0.3, -0.2),
    {{{0, 0}, {1, 0}, {0, 1}}},
    isosceles(15, 40, -2, 5),
    {{{1, 1}, {4, 1.5}, {0.5, 1.8}}}
};

//- Text of the conversion sub-dictionary with the other keywords it
//  holds, which the criteria must leave alone
const std::string otherConversionKeywords =
    "groupSizeFactor 1.2; presetParticleRegions { }";

} // End anonymous namespace


// * * * * * * * * * * * * * * minInteriorAngle  * * * * * * * * * * * * * * //

TEST(MinInteriorAngle, equilateralAndRightIsoscelesAreNotDistortedAt30Deg)
{
    const minInteriorAngle criterion(dictionaryFrom(""));
    EXPECT_EQ(criterion.limit(), 30);
    EXPECT_FALSE(distorted(criterion, isosceles(60)));
    EXPECT_FALSE(distorted(criterion, isosceles(90)));
    // Right isosceles with the right angle at each node in turn
    const triangle right{{{0, 0}, {1, 0}, {0, 1}}};
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_FALSE(distorted(criterion, rotated(right, k))) << "k = " << k;
    }
}


TEST(MinInteriorAngle, angleOf29DegIsDistortedAnd31DegIsNotWhereverTheCorner)
{
    const minInteriorAngle criterion(dictionaryFrom(otherConversionKeywords));
    for (const scalar turn : {0.0, 37.0, 200.0})
    {
        for (int k = 0; k < 3; ++k)
        {
            SCOPED_TRACE("turn " + std::to_string(turn) + " corner " + std::to_string(k));
            // Isosceles: angles 29, 75.5, 75.5 and 31, 74.5, 74.5
            EXPECT_TRUE
            (
                distorted(criterion, rotated(isosceles(29, turn, 3, -1), k))
            );
            EXPECT_FALSE
            (
                distorted(criterion, rotated(isosceles(31, turn, 3, -1), k))
            );
            // Sharp: 1e-6 deg either side of the limit
            EXPECT_TRUE
            (
                distorted(criterion, rotated(isosceles(30 - 1e-6, turn), k))
            );
            EXPECT_FALSE
            (
                distorted(criterion, rotated(isosceles(30 + 1e-6, turn), k))
            );
        }
    }
}


TEST(MinInteriorAngle, obtuseTriangleIsJudgedByItsSmallestAngle)
{
    // Apex 130 deg: base angles 25 deg, distorted; apex 110: 35, not
    const minInteriorAngle criterion(dictionaryFrom(""));
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_TRUE(distorted(criterion, rotated(isosceles(130), k)));
        EXPECT_FALSE(distorted(criterion, rotated(isosceles(110), k)));
    }
}


TEST(MinInteriorAngle, limitIsReadFromTheConversionDictionary)
{
    const minInteriorAngle at20(dictionaryFrom("minInteriorAngle 20;"));
    const minInteriorAngle at40(dictionaryFrom("minInteriorAngle 40;"));
    EXPECT_FALSE(distorted(at20, isosceles(25)));
    EXPECT_TRUE(distorted(at40, isosceles(35)));
    EXPECT_FALSE(distorted(at40, isosceles(45)));
    EXPECT_NEAR(at20.cotLimit(), 1/std::tan(degToRad(20.0)), 1e-14);
}


TEST(MinInteriorAngle, invertedCollapsedAndNaNTrianglesAreDistorted)
{
    const minInteriorAngle criterion(dictionaryFrom(""));
    const triangle equilateral = isosceles(60);
    const triangle inverted{{equilateral[0], equilateral[2], equilateral[1]}};
    EXPECT_TRUE(distorted(criterion, inverted));
    EXPECT_TRUE(distorted(criterion, triangle{{{0, 0}, {1, 0}, {2, 0}}}));
    EXPECT_TRUE(distorted(criterion, triangle{{{0, 0}, {0, 0}, {0, 0}}}));
    const scalar nan = std::numeric_limits<scalar>::quiet_NaN();
    EXPECT_TRUE(distorted(criterion, triangle{{{0, 0}, {1, 0}, {nan, 1}}}));
}


TEST(MinInteriorAngle, limitOutsideZeroToSixtyDegStopsNamingTheKeyword)
{
    for (const char* limit : {"0", "60", "75", "-5"})
    {
        SCOPED_TRACE(limit);
        fatalIOErrorOf
        (
            [&]
            {
                minInteriorAngle
                (
                    dictionaryFrom(std::string("minInteriorAngle ") + limit + ";")
                );
            },
            {"minInteriorAngle", limit}
        );
    }
}


TEST(MinInteriorAngle, describesItsLimit)
{
    OStringStream os;
    minInteriorAngle(dictionaryFrom("minInteriorAngle 25;")).describe(os);
    EXPECT_EQ(os.str(), "minInteriorAngle < 25 deg");
}


// * * * * * * * * * * * * * * * stretchRatio  * * * * * * * * * * * * * * * //

TEST(StretchRatio, rotationAndUniformScalingOfAnyReferenceAreNotDistorted)
{
    const stretchRatio criterion(dictionaryFrom(otherConversionKeywords));
    EXPECT_EQ(criterion.limit(), 3);
    for (const triangle& X : referenceTriangles)
    {
        for (const scalar angle : {0.0, 30.0, 135.0, 270.0})
        {
            for (const scalar scale : {0.5, 1.0, 2.0})
            {
                SCOPED_TRACE
                (
                    "angle " + std::to_string(angle)
                  + " scale " + std::to_string(scale)
                );
                std::array<scalar, 4> F = rotation(angle);
                for (scalar& f : F) f *= scale;
                const triangle x = mapped(X, F, 1.5, -0.7);
                EXPECT_FALSE(distorted(criterion, x, &X));
                EXPECT_NEAR(principalStretchRatio(x, X), 1, 1e-9);
            }
        }
    }
}


TEST(StretchRatio, simpleShearIsDistortedJustAboveTheLimitAndNotBelow)
{
    // det F = 1: the area is unchanged, as in a nearly incompressible fluid
    const stretchRatio criterion(dictionaryFrom(""));
    for (const triangle& X : referenceTriangles)
    {
        for (const scalar angle : {0.0, 50.0})
        {
            SCOPED_TRACE("rotated by " + std::to_string(angle));
            auto shearedBy = [&](const scalar ratio)
            {
                return mapped
                (
                    X, product(rotation(angle), simpleShearWithRatio(ratio)),
                    0.2, 0.1
                );
            };
            for (const scalar ratio : {1.5, 3.0, 10.0})
            {
                EXPECT_NEAR
                (
                    principalStretchRatio(shearedBy(ratio), X), ratio,
                    1e-9*ratio
                );
            }
            const triangle below = shearedBy(3*(1 - 1e-6));
            const triangle above = shearedBy(3*(1 + 1e-6));
            EXPECT_FALSE(distorted(criterion, below, &X));
            EXPECT_TRUE(distorted(criterion, above, &X));
        }
    }
}


TEST(StretchRatio, limitIsReadFromTheConversionDictionary)
{
    const stretchRatio criterion(dictionaryFrom("maxStretchRatio 5;"));
    const triangle& X = referenceTriangles[1];
    EXPECT_FALSE(distorted(criterion, mapped(X, simpleShearWithRatio(4.9)), &X));
    EXPECT_TRUE(distorted(criterion, mapped(X, simpleShearWithRatio(5.1)), &X));
}


TEST(StretchRatio, reflectionFlatteningAndCollapseAreDistorted)
{
    const stretchRatio criterion(dictionaryFrom(""));
    for (const triangle& X : referenceTriangles)
    {
        // Mirror image: stretch ratio 1 but det F = -1
        const triangle mirrored = mapped(X, {-1, 0, 0, 1});
        EXPECT_NEAR(principalStretchRatio(mirrored, X), 1, 1e-9);
        EXPECT_TRUE(distorted(criterion, mirrored, &X));
        // Flattened onto the x axis, or collapsed to a point: det F = 0
        EXPECT_TRUE(distorted(criterion, mapped(X, {1, 0, 0, 0}), &X));
        EXPECT_TRUE(distorted(criterion, mapped(X, {0, 0, 0, 0}, 1, 2), &X));
    }
}


TEST(StretchRatio, poorButUndeformedReferenceIsNotDistortedUnlikeMinInteriorAngle)
{
    // The 15 deg sliver of the initial mesh: the MIA converts it at t = 0,
    // the stretch ratio measures only what the flow did to it
    const triangle& sliver = referenceTriangles[2];
    EXPECT_TRUE(distorted(minInteriorAngle(dictionaryFrom("")), sliver));
    EXPECT_FALSE(distorted(stretchRatio(dictionaryFrom("")), sliver, &sliver));
}


TEST(StretchRatio, limitNotAboveOneStopsNamingTheKeyword)
{
    for (const char* limit : {"1", "0.5", "-2"})
    {
        SCOPED_TRACE(limit);
        fatalIOErrorOf
        (
            [&]
            {
                stretchRatio
                (
                    dictionaryFrom(std::string("maxStretchRatio ") + limit + ";")
                );
            },
            {"maxStretchRatio", limit}
        );
    }
}


// * * * * * * * * * * * * * * * * Selection * * * * * * * * * * * * * * * * //

TEST(DistortionCriterionSelection, selectedByCriterionKeywordWithMinInteriorAngleDefault)
{
    EXPECT_EQ
    (
        distortionCriterion::New(dictionaryFrom(""))->type(),
        "minInteriorAngle"
    );
    EXPECT_EQ
    (
        distortionCriterion::New
        (
            dictionaryFrom(otherConversionKeywords + " minInteriorAngle 20;")
        )->type(),
        "minInteriorAngle"
    );
    EXPECT_EQ
    (
        distortionCriterion::New
        (
            dictionaryFrom("criterion stretchRatio; " + otherConversionKeywords)
        )->type(),
        "stretchRatio"
    );

    // The selected object reads its own coefficient
    OStringStream os;
    distortionCriterion::New
    (
        dictionaryFrom("criterion minInteriorAngle; minInteriorAngle 20;")
    )->describe(os);
    EXPECT_EQ(os.str(), "minInteriorAngle < 20 deg");

    OStringStream stretchOs;
    distortionCriterion::New
    (
        dictionaryFrom("criterion stretchRatio; maxStretchRatio 4;")
    )->describe(stretchOs);
    EXPECT_EQ
    (
        stretchOs.str(), "stretchRatio > 4 (principal stretches since t = 0)"
    );
}


TEST(DistortionCriterionSelection, markingARangeGivesEachElementsDistorted)
{
    // markDistortedWithSlack() (one virtual call per range,
    // groupConversion's whole passes) against distorted() element by
    // element, for every model, on a range long enough to be split among
    // threads (above minParallelLoop) and a short one, of randomly sheared
    // triangles
    const label nElements = 3*minParallelLoop + 17;
    std::vector<scalar> X, x;
    std::vector<label> nodes;
    unsigned seed = 12345;
    const auto random = [&seed]()
    {
        seed = 1103515245u*seed + 12345u;
        return scalar((seed >> 8) & 0xffff)/0xffff;
    };
    for (label e = 0; e < nElements; ++e)
    {
        // Reference triangles of different shapes (their edges tell them
        // apart)
        const scalar stretch = 0.5 + random();
        const scalar ref[6] = {0, 0, stretch, 0, 0, 1};
        for (label k = 0; k < 3; ++k)
        {
            nodes.push_back(label(X.size()/2));
            X.push_back(ref[2*k] + e);
            X.push_back(ref[2*k + 1]);
            // Up to 60 % of an edge: some distorted, some not, some inverted
            x.push_back(ref[2*k] + e + 0.6*(random() - 0.5));
            x.push_back(ref[2*k + 1] + 0.6*(random() - 0.5));
        }
    }
    // The elements' mesh triangles in reverse order, each triangle's
    // reference edges at its own place
    std::vector<label> triangle(nElements);
    std::vector<scalar> edges(4*nElements);
    for (label e = 0; e < nElements; ++e)
    {
        triangle[e] = nElements - 1 - e;
        const label* n = &nodes[3*e];
        distortionCriterion::referenceEdges
        (
            &X[2*n[0]], &X[2*n[1]], &X[2*n[2]], &edges[4*triangle[e]]
        );
    }
    for
    (
        const std::string criterion :
        {"minInteriorAngle", "stretchRatio", "none"}
    )
    {
        SCOPED_TRACE(criterion);
        const autoPtr<distortionCriterion> c = distortionCriterion::New
        (
            dictionaryFrom("criterion " + criterion + ";")
        );
        for (const label end : {nElements, label(40)})
        {
            std::vector<unsigned char> marked(nElements, 7);
            std::vector<scalar> slack(nElements, -1);
            c->markDistortedWithSlack
            (
                0, end, nodes.data(), x.data(), triangle.data(), edges.data(),
                marked.data(), slack.data()
            );
            label nDistorted = 0;
            for (label e = 0; e < end; ++e)
            {
                const label* n = &nodes[3*e];
                const bool expected = c->distorted
                (
                    &x[2*n[0]], &x[2*n[1]], &x[2*n[2]],
                    &X[2*n[0]], &X[2*n[1]], &X[2*n[2]]
                );
                ASSERT_EQ(bool(marked[e]), expected) << "element " << e;
                nDistorted += expected;
            }
            for (label e = end; e < nElements; ++e)
            {
                ASSERT_EQ(marked[e], 7) << "written outside the range";
                ASSERT_EQ(slack[e], -1) << "written outside the range";
            }
            if (criterion != "none" && end == nElements)
            {
                EXPECT_GT(nDistorted, 0);
                EXPECT_LT(nDistorted, end);
            }
        }
    }
}


TEST(DistortionCriterionSelection, noMoveWithinTheSlackMakesAnUndistortedElementDistorted)
{
    // markDistortedWithSlack(): the flags of distorted(), and a slack
    // such that no move of the nodes within it (in x and in y) makes the
    // element distorted, which groupConversion relies on to skip the test
    // of elements whose nodes have not moved that far. Randomly sheared
    // triangles; for each undistorted one, its nodes moved to every
    // corner of the slack's box (the 64 sign choices of +-slack in x and
    // y of three nodes) and to random points inside it. The slack is
    // about a tenth of the way to the nearest distorted move found along
    // those directions (printed): the bound is not empty
    const label nElements = 2000;
    std::vector<scalar> X, x;
    std::vector<label> nodes;
    std::mt19937 gen(4321);
    std::uniform_real_distribution<scalar> u(-1, 1);
    for (label e = 0; e < nElements; ++e)
    {
        const scalar stretch = 1 + 0.5*u(gen);
        const scalar ref[6] = {0, 0, stretch, 0, 0.3*u(gen), 1};
        for (label k = 0; k < 3; ++k)
        {
            nodes.push_back(label(X.size()/2));
            X.push_back(ref[2*k] + 3*e);
            X.push_back(ref[2*k + 1]);
            x.push_back(ref[2*k] + 3*e + 0.3*u(gen));
            x.push_back(ref[2*k + 1] + 0.3*u(gen));
        }
    }
    std::vector<label> triangle(nElements);
    std::vector<scalar> edges(4*nElements);
    for (label e = 0; e < nElements; ++e)
    {
        triangle[e] = e;
        const label* n = &nodes[3*e];
        distortionCriterion::referenceEdges
        (
            &X[2*n[0]], &X[2*n[1]], &X[2*n[2]], &edges[4*e]
        );
    }
    for (const std::string criterion : {"minInteriorAngle", "stretchRatio"})
    {
        SCOPED_TRACE(criterion);
        const autoPtr<distortionCriterion> c = distortionCriterion::New
        (
            dictionaryFrom("criterion " + criterion + ";")
        );
        std::vector<unsigned char> flags(nElements), withSlack(nElements);
        std::vector<scalar> slack(nElements, -1);
        for (label e = 0; e < nElements; ++e)
        {
            const label* n = &nodes[3*e];
            flags[e] = c->distorted
            (
                &x[2*n[0]], &x[2*n[1]], &x[2*n[2]],
                &X[2*n[0]], &X[2*n[1]], &X[2*n[2]]
            );
        }
        c->markDistortedWithSlack
        (
            0, nElements, nodes.data(), x.data(), triangle.data(),
            edges.data(), withSlack.data(), slack.data()
        );
        // markDistortedOf() of a list in another order: the same flags
        std::vector<label> list(nElements);
        for (label e = 0; e < nElements; ++e) list[e] = nElements - 1 - e;
        std::vector<unsigned char> ofList(nElements);
        c->markDistortedOf
        (
            list.data(), nElements, nodes.data(), x.data(), triangle.data(),
            edges.data(), ofList.data()
        );
        label nUndistorted = 0, nWithSlack = 0;
        std::vector<scalar> ratios;
        for (label e = 0; e < nElements; ++e)
        {
            ASSERT_EQ(withSlack[e], flags[e]) << "element " << e;
            ASSERT_EQ(ofList[nElements - 1 - e], flags[e]) << "element " << e;
            if (flags[e])
            {
                EXPECT_EQ(slack[e], 0) << "element " << e;
                continue;
            }
            ++nUndistorted;
            ASSERT_GE(slack[e], 0) << "element " << e;
            if (slack[e] == 0) continue;
            ++nWithSlack;
            const label* n = &nodes[3*e];
            const auto distortedMoved = [&](const scalar* move)
            {
                scalar y[6];
                for (label k = 0; k < 3; ++k)
                {
                    y[2*k] = x[2*n[k]] + move[2*k];
                    y[2*k + 1] = x[2*n[k] + 1] + move[2*k + 1];
                }
                return c->distorted
                (
                    y, y + 2, y + 4, &X[2*n[0]], &X[2*n[1]], &X[2*n[2]]
                );
            };
            scalar nearest = VGREAT;
            for (label signs = 0; signs < 64; ++signs)
            {
                scalar move[6];
                for (label i = 0; i < 6; ++i)
                {
                    move[i] = (signs >> i & 1) ? slack[e] : -slack[e];
                }
                ASSERT_FALSE(distortedMoved(move))
                    << "element " << e << ", corner " << signs;
                // The distorted move nearest along this direction
                for (scalar f = 1.25; f < 1000; f *= 1.25)
                {
                    scalar far[6];
                    for (label i = 0; i < 6; ++i) far[i] = f*move[i];
                    if (distortedMoved(far))
                    {
                        nearest = std::min(nearest, f);
                        break;
                    }
                }
            }
            for (label trial = 0; trial < 64; ++trial)
            {
                scalar move[6];
                for (scalar& m : move) m = slack[e]*u(gen);
                ASSERT_FALSE(distortedMoved(move))
                    << "element " << e << ", trial " << trial;
            }
            if (nearest < VGREAT) ratios.push_back(nearest);
        }
        // Most undistorted elements have a slack (the others lie within
        // 1e-9 of the limit: none here)
        EXPECT_EQ(nWithSlack, nUndistorted);
        EXPECT_GT(nUndistorted, nElements/4);
        EXPECT_LT(nUndistorted, nElements);
        ASSERT_FALSE(ratios.empty());
        std::sort(ratios.begin(), ratios.end());
        const scalar median = ratios[ratios.size()/2];
        std::cout << criterion << ": " << nUndistorted << " undistorted;"
            << " the nearest distorted move along the slack's corners is "
            << ratios.front() << " to " << ratios.back()
            << " slacks (median " << median << ")" << std::endl;
        // Not an empty bound: the median element distorts within a few
        // slacks along some corner direction (measured: 6)
        EXPECT_LT(median, 20);
    }
}


TEST(DistortionCriterionSelection, unknownCriterionStopsListingValidNames)
{
    const std::string message = fatalIOErrorOf
    (
        [] { distortionCriterion::New(dictionaryFrom("criterion jacobian;")); },
        {"jacobian", "criterion", "minInteriorAngle", "stretchRatio"}
    );
    std::cout << "FatalIOError message:\n" << message << std::endl;
}


// * * * * * * * * * * * * * * Preset regions  * * * * * * * * * * * * * * * //

namespace
{

//- A 1 x 1 square of 4 x 4 cells, patches left, right, bottom, top
const triMesh& unitSquare()
{
    static const triMesh mesh = testMeshes::build({{0, 1, 0, 1, 4, 4, "water"}});
    return mesh;
}

//- Region `name` of the given text (the region's sub-dictionary entries)
autoPtr<presetParticleRegion> regionFrom
(
    const std::string& entries,
    const triMesh& mesh = unitSquare()
)
{
    return presetParticleRegion::New("test", dictionaryFrom(entries), mesh);
}

} // End anonymous namespace


TEST(PresetParticleRegions, boxContainsItsInsideAndBoundaryOnly)
{
    const autoPtr<presetParticleRegion> box =
        regionFrom("type box; min (-1 0 0); max (2 0.5 0);");
    EXPECT_EQ(box->type(), "box");
    EXPECT_EQ(box->name(), "test");
    EXPECT_TRUE(box->contains(0, 0.25));
    EXPECT_TRUE(box->contains(-1, 0));      // corner
    EXPECT_TRUE(box->contains(2, 0.5));     // corner
    EXPECT_FALSE(box->contains(-1.01, 0.25));
    EXPECT_FALSE(box->contains(2.01, 0.25));
    EXPECT_FALSE(box->contains(0, -0.01));
    EXPECT_FALSE(box->contains(0, 0.51));
}


TEST(PresetParticleRegions, circleContainsPointsWithinItsRadius)
{
    const autoPtr<presetParticleRegion> circle =
        regionFrom("type circle; centre (1 -2 0); radius 0.5;");
    EXPECT_EQ(circle->type(), "circle");
    EXPECT_TRUE(circle->contains(1, -2));
    EXPECT_TRUE(circle->contains(1.3, -2.3));  // 0.42 from the centre
    EXPECT_TRUE(circle->contains(1, -1.5));    // on the circle
    EXPECT_FALSE(circle->contains(1.4, -2.4)); // 0.57 from the centre
    EXPECT_FALSE(circle->contains(0, 0));
}


TEST(PresetParticleRegions, nonConvexPolygonExcludesItsNotchInEitherOrientation)
{
    // L-shape: the unit square [1, 2] x [1, 2] is cut out of [0, 2]^2
    const char* counterClockwise =
        "((0 0 0) (2 0 0) (2 1 0) (1 1 0) (1 2 0) (0 2 0))";
    const char* clockwise =
        "((0 2 0) (1 2 0) (1 1 0) (2 1 0) (2 0 0) (0 0 0))";
    for (const char* points : {counterClockwise, clockwise})
    {
        SCOPED_TRACE(points);
        const autoPtr<presetParticleRegion> L =
            regionFrom(std::string("type polygon; points ") + points + ";");
        EXPECT_EQ(L->type(), "polygon");
        EXPECT_TRUE(L->contains(0.5, 0.5));
        EXPECT_TRUE(L->contains(1.5, 0.5));
        EXPECT_TRUE(L->contains(0.5, 1.5));
        EXPECT_TRUE(L->contains(0.5, 1));      // ray through the vertex (1 1)
        EXPECT_TRUE(L->contains(1.99, 0.99));
        EXPECT_FALSE(L->contains(1.5, 1.5));   // the notch
        EXPECT_FALSE(L->contains(1.01, 1.01));
        EXPECT_FALSE(L->contains(-0.1, 0.5));
        EXPECT_FALSE(L->contains(2.5, 0.5));
        EXPECT_FALSE(L->contains(0.5, 2.5));
        EXPECT_FALSE(L->contains(0.5, -0.5));
    }
}


TEST(PresetParticleRegions, patchDistanceSelectsPointsNearItsPatchesOnly)
{
    const autoPtr<presetParticleRegion> bottom =
        regionFrom("type patchDistance; patches (bottom); distance 0.2;");
    EXPECT_EQ(bottom->type(), "patchDistance");
    EXPECT_EQ
    (
        dynamic_cast<const patchDistanceRegion&>(*bottom).nSegments(), 4
    );
    EXPECT_TRUE(bottom->contains(0.5, 0.1));
    EXPECT_TRUE(bottom->contains(0.5, 0.2));
    EXPECT_TRUE(bottom->contains(0.5, -0.15));   // outside the mesh, too
    EXPECT_TRUE(bottom->contains(1.1, -0.1));    // 0.14 from the corner
    EXPECT_FALSE(bottom->contains(0.5, 0.25));
    EXPECT_FALSE(bottom->contains(1.2, -0.2));   // 0.28 from the corner
    EXPECT_FALSE(bottom->contains(0.05, 0.5));   // near left, not bottom
    EXPECT_FALSE(bottom->contains(0.5, 0.95));   // near top, not bottom

    const autoPtr<presetParticleRegion> bottomAndLeft =
        regionFrom("type patchDistance; patches (bottom left); distance 0.2;");
    EXPECT_TRUE(bottomAndLeft->contains(0.05, 0.5));
    EXPECT_FALSE(bottomAndLeft->contains(0.95, 0.5));
}


TEST(PresetParticleRegions, patchDistanceSelectsPointsNearARigidBody)
{
    // A cylinder of radius 0.2 at (0.5, 0.5) and a wedge-like triangle
    const rigidBodies bodies
    (
        dictionaryFrom
        (
            "bodies {"
            " cylinder { shape circle; centre (0.5 0.5 0); radius 0.2;"
            " motion prescribed; velocity (0 0 0); }"
            " wedge { shape polygon; points ((2 0 0) (3 0 0) (2.5 1 0));"
            " motion prescribed; velocity (0 0 0); } }"
        )
    );
    const triMesh mesh = unitSquare();
    const autoPtr<presetParticleRegion> nearCylinder = presetParticleRegion::New
    (
        "test",
        dictionaryFrom("type patchDistance; bodies (cylinder); distance 0.1;"),
        mesh, bodies.surfaces()
    );
    EXPECT_TRUE(nearCylinder->contains(0.5, 0.5));      // inside the body
    EXPECT_TRUE(nearCylinder->contains(0.79, 0.5));     // 0.09 from it
    EXPECT_FALSE(nearCylinder->contains(0.81, 0.5));    // 0.11 from it
    EXPECT_FALSE(nearCylinder->contains(0.5, 0.05));    // near bottom only
    EXPECT_FALSE(nearCylinder->contains(2.5, -0.05));   // near the wedge

    // Patches and bodies together: the union
    const autoPtr<presetParticleRegion> both = presetParticleRegion::New
    (
        "test",
        dictionaryFrom
        (
            "type patchDistance; patches (bottom); bodies (wedge);"
            " distance 0.1;"
        ),
        mesh, bodies.surfaces()
    );
    EXPECT_TRUE(both->contains(0.5, 0.05));
    EXPECT_TRUE(both->contains(2.5, -0.05));
    EXPECT_FALSE(both->contains(0.79, 0.5));

    // A body that does not exist, no bodies at all, nothing to measure from
    fatalIOErrorOf
    (
        [&]
        {
            presetParticleRegion::New
            (
                "test",
                dictionaryFrom("type patchDistance; bodies (sphere); distance 0.1;"),
                mesh, bodies.surfaces()
            );
        },
        {"sphere", "cylinder", "wedge"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type patchDistance; bodies (cylinder); distance 0.1;"); },
        {"cylinder"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type patchDistance; distance 0.1;"); },
        {"patches", "bodies"}
    );
}


TEST(PresetParticleRegions, patchDistanceSelectsTheFirstRowOfElementCentroids)
{
    // Rows of cells 0.25 high: the centroids of the first row lie at
    // y = 1/12 or 1/6, those of the second at 1/3 or 5/12
    const triMesh& mesh = unitSquare();
    const autoPtr<presetParticleRegion> bottom =
        regionFrom("type patchDistance; patches (bottom); distance 0.25;");
    const std::vector<scalar>& p = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    label nSelected = 0;
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        scalar cx = 0, cy = 0;
        for (int i = 0; i < 3; ++i)
        {
            cx += p[2*tri[3*t + i]]/3;
            cy += p[2*tri[3*t + i] + 1]/3;
        }
        const bool selected = bottom->contains(cx, cy);
        EXPECT_EQ(selected, cy < 0.25) << "centroid (" << cx << ' ' << cy << ')';
        nSelected += selected;
    }
    EXPECT_EQ(nSelected, 8);
}


TEST(PresetParticleRegions, unknownPatchStopsListingTheMeshPatches)
{
    const std::string message = fatalIOErrorOf
    (
        [] { regionFrom("type patchDistance; patches (bottom floor); distance 0.1;"); },
        {"floor", "patches", "left", "right", "bottom", "top"}
    );
    std::cout << "FatalIOError message:\n" << message << std::endl;
}


TEST(PresetParticleRegions, unknownKeywordStopsNamingIt)
{
    fatalIOErrorOf
    (
        [] { regionFrom("type patchDistance; patches (bottom); distanse 0.1;"); },
        {"distanse"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type box; min (0 0 0); max (1 1 0); radius 1;"); },
        {"radius"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type circle; centre (0 0 0); radius 1; min (0 0 0);"); },
        {"min"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type polygon; points ((0 0 0) (1 0 0) (0 1 0)); closed yes;"); },
        {"closed"}
    );
}


TEST(PresetParticleRegions, badValuesStopNamingTheKeyword)
{
    fatalIOErrorOf
    (
        [] { regionFrom("type box; min (0 0 0); max (1 0 0);"); },
        {"max"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type box; min (0 0 0); max (-1 1 0);"); },
        {"max"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type circle; centre (0 0 0); radius 0;"); },
        {"radius"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type polygon; points ((0 0 0) (1 0 0));"); },
        {"points", "at least 3"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type polygon; points ((0 0 0) (1 1 0) (2 2 0));"); },
        {"points", "no area"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type patchDistance; patches (bottom); distance -0.1;"); },
        {"distance"}
    );
    fatalIOErrorOf
    (
        [] { regionFrom("type patchDistance; patches (); distance 0.1;"); },
        {"patches"}
    );
}


TEST(PresetParticleRegions, unknownTypeStopsListingValidTypes)
{
    fatalIOErrorOf
    (
        [] { regionFrom("type sphere; centre (0 0 0); radius 1;"); },
        {"sphere", "box", "circle", "polygon", "patchDistance"}
    );
}


TEST(PresetParticleRegions, readsEveryRegionOfTheConversionDictionary)
{
    const triMesh& mesh = unitSquare();

    EXPECT_EQ(readPresetParticleRegions(dictionaryFrom(""), mesh).size(), 0);
    EXPECT_EQ
    (
        readPresetParticleRegions
        (
            dictionaryFrom("presetParticleRegions { }"), mesh
        ).size(),
        0
    );

    const PtrList<presetParticleRegion> regions = readPresetParticleRegions
    (
        dictionaryFrom
        (
            "criterion minInteriorAngle; groupSizeFactor 1.2;"
            "presetParticleRegions"
            "{"
            "    aroundCylinder { type circle; centre (0.5 0.5 0); radius 0.1; }"
            "    nearBottom { type patchDistance; patches (bottom); distance 0.1; }"
            "}"
        ),
        mesh
    );
    ASSERT_EQ(regions.size(), 2);
    EXPECT_EQ(regions[0].name(), "aroundCylinder");
    EXPECT_EQ(regions[0].type(), "circle");
    EXPECT_EQ(regions[1].name(), "nearBottom");
    EXPECT_EQ(regions[1].type(), "patchDistance");
    EXPECT_TRUE(regions[0].contains(0.55, 0.5));
    EXPECT_FALSE(regions[1].contains(0.55, 0.5));

    fatalIOErrorOf
    (
        [&]
        {
            readPresetParticleRegions
            (
                dictionaryFrom("presetParticleRegions { box1 box; }"), mesh
            );
        },
        {"box1", "sub-dictionary"}
    );
    fatalIOErrorOf
    (
        [&]
        {
            readPresetParticleRegions
            (
                dictionaryFrom("presetParticleRegions (a b);"), mesh
            );
        },
        {"presetParticleRegions"}
    );
}
