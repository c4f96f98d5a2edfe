/*---------------------------------------------------------------------------*\
Description
    Unit tests of the loop helpers of src/SPEM/core/parallelLoop:
    parallelFor, parallelAll and parallelAllMin visit every index of the
    range exactly once and give the serial loop's result, below the size
    at which they share the range among threads (no parallel region) and
    above it (an OpenMP region on the threads there are); parallelAll
    does not stop at the first false.

\*---------------------------------------------------------------------------*/

#include "parallelLoop.H"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

using namespace Foam;

namespace
{

// Below and above the default size of a shared loop
const std::vector<label> sizes = {0, 1, 7, minParallelLoop, 3*minParallelLoop + 5};

} // End anonymous namespace


TEST(ParallelLoop, parallelForVisitsEveryIndexOnce)
{
    for (const label n : sizes)
    {
        SCOPED_TRACE(n);
        const label begin = 3;
        std::vector<int> visits(n + begin, 0);
        parallelFor(begin, begin + n, [&](const label i) { ++visits[i]; });
        for (label i = 0; i < begin; ++i) EXPECT_EQ(visits[i], 0);
        for (label i = begin; i < begin + n; ++i) ASSERT_EQ(visits[i], 1) << i;
    }
}


TEST(ParallelLoop, parallelAllIsTheConjunctionAndVisitsEveryIndex)
{
    for (const label n : sizes)
    {
        SCOPED_TRACE(n);
        std::vector<int> visits(n, 0);
        // All true
        EXPECT_TRUE
        (
            parallelAll(0, n, [&](const label i) { ++visits[i]; return true; })
        );
        // One false, in the middle: false, and still every index visited
        const label bad = n/2;
        EXPECT_EQ
        (
            parallelAll
            (
                0, n, [&](const label i) { ++visits[i]; return i != bad; }
            ),
            n == 0
        );
        for (label i = 0; i < n; ++i) ASSERT_EQ(visits[i], 2) << i;
    }
}


TEST(ParallelLoop, parallelAllMinGivesTheLeastAndTheConjunction)
{
    for (const label n : sizes)
    {
        SCOPED_TRACE(n);
        // Values 1 + (i*7919 mod n): the least is 1, at i = 0
        double least = std::numeric_limits<double>::max();
        const bool all = parallelAllMin
        (
            0, n, least,
            [&](const label i, double& m)
            {
                m = std::min(m, 1.0 + double((i*7919) % n));
                return true;
            }
        );
        EXPECT_TRUE(all);
        EXPECT_EQ(least, n ? 1.0 : std::numeric_limits<double>::max());

        // A start value below every item's is kept
        double start = 0.5;
        EXPECT_FALSE
        (
            parallelAllMin
            (
                0, n + 1, start,
                [&](const label i, double& m)
                {
                    m = std::min(m, 2.0 + i);
                    return i != 0;
                }
            )
        );
        EXPECT_EQ(start, 0.5);
    }
}

// ************************************************************************* //
