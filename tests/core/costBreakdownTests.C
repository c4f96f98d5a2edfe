/*---------------------------------------------------------------------------*\
Description
    Unit tests of costBreakdown, the log's breakdown of the wall time:
    nested parts are charged their own time only, so that the parts add up
    to the wall time of the loop and none is counted twice.

\*---------------------------------------------------------------------------*/

#include "costBreakdown.H"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

using Foam::costBreakdown;

namespace
{

//- Wall seconds of f()
template<class F>
double wallOf(F f)
{
    const auto start = costBreakdown::clock::now();
    f();
    return std::chrono::duration<double>
    (
        costBreakdown::clock::now() - start
    ).count();
}

void sleepMs(const int ms)
{
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

} // End anonymous namespace


TEST(CostBreakdown, nestedPartsAreChargedTheirOwnTimeOnly)
{
    costBreakdown cost;
    cost.startLoop();
    // conversion 20 ms, of which its couplings 30 ms in the middle
    const double wall = wallOf
    (
        [&cost]()
        {
            const costBreakdown::scope outer(cost, costBreakdown::conversion);
            sleepMs(10);
            {
                const costBreakdown::scope inner
                (
                    cost, costBreakdown::couplings
                );
                sleepMs(30);
            }
            sleepMs(10);
        }
    );
    const double outer = cost.seconds(costBreakdown::conversion);
    const double inner = cost.seconds(costBreakdown::couplings);
    // A sleep lasts at least as long as asked
    EXPECT_GE(inner, 0.030);
    EXPECT_GE(outer, 0.020);
    // The two are the scope's wall, split at the clock reads of the
    // switches: counted twice, they would exceed it by the inner 30 ms
    EXPECT_NEAR(outer + inner, wall, 1e-3);
    EXPECT_EQ(cost.seconds(costBreakdown::elements), 0);
}


TEST(CostBreakdown, partsNotEnteredStayZeroAndStartLoopClearsAll)
{
    costBreakdown cost;
    {
        const costBreakdown::scope timed(cost, costBreakdown::output);
        sleepMs(2);
    }
    EXPECT_GT(cost.seconds(costBreakdown::output), 0);
    cost.startLoop();
    for (int p = 0; p < costBreakdown::nParts; ++p)
    {
        EXPECT_EQ(cost.seconds(costBreakdown::part(p)), 0) << p;
    }
    // Time outside any part is the loop's "other", charged to no part
    sleepMs(2);
    for (int p = 0; p < costBreakdown::nParts; ++p)
    {
        EXPECT_EQ(cost.seconds(costBreakdown::part(p)), 0) << p;
    }
    EXPECT_GE(cost.wall(), 0.002);
}


// ************************************************************************* //
