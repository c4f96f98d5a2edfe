/*---------------------------------------------------------------------------*\
Description
    Unit tests of src/SPEM/core/simdLanes: a pair's helpers are the scalar
    functions lane by lane (std::max and std::min with NaN and signed
    zeros, std::sqrt), the pair loops visit every item once, as pairs and
    the odd last one as a scalar, and give the serial loop's least; and a
    kernel written on both value types gives the scalar results to the
    bit: the fluid's stress of an odd number of domains at once (pairs and
    a scalar) against each domain alone (a scalar), with and without bulk
    viscosity. The element passes' pairs are shown the same way by the
    tutorials' written states (bin/tools/compareStates, unchanged by them).

\*---------------------------------------------------------------------------*/

#include "simdLanes.H"
#include "spemMaterial.H"
#include "IStringStream.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace Foam;

namespace
{

//- Same bits (NaN equal to itself, -0 not +0)
bool sameBits(const scalar a, const scalar b)
{
    return std::memcmp(&a, &b, sizeof(scalar)) == 0;
}

const scalar nan = std::numeric_limits<scalar>::quiet_NaN();

const std::vector<scalar> awkward =
    {1.5, -2.0, 0.0, -0.0, nan, 1.5, std::numeric_limits<scalar>::max()};

} // End anonymous namespace


TEST(SimdLanes, maxAndMinAreStdMaxAndMinLaneByLane)
{
    for (const scalar a0 : awkward)
    {
        for (const scalar b0 : awkward)
        {
            // Lane 1 the other way round
            const simd::pair a{a0, b0}, b{b0, a0};
            const simd::pair mx = simd::max(a, b), mn = simd::min(a, b);
            EXPECT_TRUE(sameBits(mx[0], std::max(a0, b0))) << a0 << ' ' << b0;
            EXPECT_TRUE(sameBits(mx[1], std::max(b0, a0))) << b0 << ' ' << a0;
            EXPECT_TRUE(sameBits(mn[0], std::min(a0, b0))) << a0 << ' ' << b0;
            EXPECT_TRUE(sameBits(mn[1], std::min(b0, a0))) << b0 << ' ' << a0;
            EXPECT_TRUE(sameBits(simd::max(a0, b0), std::max(a0, b0)));
            EXPECT_TRUE(sameBits(simd::min(a0, b0), std::min(a0, b0)));
        }
    }
}


TEST(SimdLanes, sqrtGatherAndScatterWorkLaneByLane)
{
    const std::vector<scalar> x{2.0, 1e-300, 0.0, -1.0, 3.0};
    for (size_t i = 0; i + 1 < x.size(); ++i)
    {
        const simd::pair v =
            simd::gather<simd::pair>([&](const label l) { return x[i + l]; });
        const simd::pair r = simd::sqrt(v);
        scalar out[2] = {0, 0};
        simd::scatter(r, [&](const label l) -> scalar& { return out[l]; });
        for (label l = 0; l < 2; ++l)
        {
            EXPECT_TRUE(sameBits(out[l], std::sqrt(x[i + l]))) << x[i + l];
            EXPECT_TRUE(sameBits(simd::lane(r, l), out[l]));
        }
    }
}


TEST(SimdLanes, pairLoopsVisitEveryItemOnceAsPairsAndTheOddLastAsAScalar)
{
    // Below and above the size at which the loops share among threads
    for (const label n : {label(0), label(1), label(2), label(7), 4*minParallelLoop + 1})
    {
        const label begin = 3, end = begin + n;
        std::vector<int> visits(end, 0), lanesOf(end, 0);
        simd::parallelForPairs(begin, end, [&](const auto tag, const label i)
        {
            using V = typename decltype(tag)::type;
            for (label l = 0; l < simd::lanes<V>::size; ++l)
            {
                ++visits[i + l];
                lanesOf[i + l] = simd::lanes<V>::size;
            }
        });
        for (label i = 0; i < end; ++i)
        {
            EXPECT_EQ(visits[i], i >= begin ? 1 : 0) << "n " << n << " i " << i;
            if (i >= begin)
            {
                const bool oddLast = n % 2 == 1 && i == end - 1;
                EXPECT_EQ(lanesOf[i], oddLast ? 1 : 2) << "n " << n << " i " << i;
            }
        }

        // The least and the conjunction of the serial loop
        std::vector<scalar> value(end);
        for (label i = 0; i < end; ++i) value[i] = std::cos(0.37*i) + 2;
        if (n > 0) value[end - 1] = 0.5;   // the odd last one may be least
        scalar serialLeast = 10;
        for (label i = begin; i < end; ++i) serialLeast = std::min(serialLeast, value[i]);
        scalar least = 10;
        const bool all = simd::parallelAllMinPairs
        (
            begin, end, least,
            [&](const auto tag, const label i, scalar& m)
            {
                using V = typename decltype(tag)::type;
                bool ok = true;
                for (label l = 0; l < simd::lanes<V>::size; ++l)
                {
                    m = std::min(m, value[i + l]);
                    ok = ok && value[i + l] > 1;
                }
                return ok;
            }
        );
        EXPECT_EQ(least, serialLeast) << "n " << n;
        EXPECT_EQ(all, n == 0) << "n " << n;
    }
}


TEST(SimdLanes, fluidStressOfPairsIsTheScalarsToTheBit)
{
    for (const std::string bulk : {"", " bulkViscosity 0.4;"})
    {
        IStringStream is
        (
            "model weaklyCompressibleNewtonian; rho 1000; c 30; mu 1e-3;"
          + bulk
        );
        const dictionary dict(is);
        const autoPtr<spemMaterial> water = spemMaterial::New("water", dict);

        // An odd number of domains: four pairs and a scalar at once
        const label n = 9;
        std::mt19937 gen(5);
        std::uniform_real_distribution<scalar> u(-1, 1);
        std::vector<scalar> grad(4*n), area(n), mass(n);
        for (label k = 0; k < n; ++k)
        {
            for (label i = 0; i < 4; ++i) grad[4*k + i] = 3*u(gen);
            area[k] = 1e-4*(1.2 + u(gen));
            mass[k] = 1000*area[k]*(1 + 0.01*u(gen));
        }
        std::vector<scalar> together(4*n), alone(4*n);
        ASSERT_TRUE
        (
            water->stress
            (
                0, n, grad.data(), area.data(), mass.data(), together.data()
            )
        );
        for (label k = 0; k < n; ++k)
        {
            ASSERT_TRUE
            (
                water->stress
                (
                    k, k + 1, grad.data(), area.data(), mass.data(),
                    alone.data()
                )
            );
        }
        for (label i = 0; i < 4*n; ++i)
        {
            EXPECT_TRUE(sameBits(together[i], alone[i]))
                << "entry " << i << ": " << together[i] << " against "
                << alone[i] << (bulk.empty() ? "" : " (bulk viscosity)");
        }
    }
}


// ************************************************************************* //
