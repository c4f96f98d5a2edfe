/*---------------------------------------------------------------------------*\
Description
    Unit tests of the loop helpers of src/SPEM/core/parallelLoop:
    parallelFor, parallelAll and parallelAllMin visit every index of the
    range exactly once and give the serial loop's result, below the size
    at which they share the range among threads (no parallel region) and
    above it (an OpenMP region on the threads there are); parallelAll
    does not stop at the first false. threadBlock cuts a range into
    contiguous blocks in thread order that cover it once, for any team
    size; a threadTeam's sync() makes what each thread wrote before it
    visible to all after it, over many passes in a row; a helper loop
    inside a team opens no region of its own; teamOrOne tries one thread
    and the team, then runs the faster, tries the other every trialEvery
    calls and follows a change of the machine.

\*---------------------------------------------------------------------------*/

#include "parallelLoop.H"

#include <gtest/gtest.h>

#include <limits>
#include <numeric>
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

TEST(ParallelLoop, threadBlocksCoverTheRangeOnceInThreadOrder)
{
    for (const label n : {0, 1, 2, 5, 1000, 1001})
    {
        #pragma omp parallel num_threads(3)
        {
            label b, e;
            threadBlock(7, 7 + n, b, e);
            #pragma omp critical
            {
                SCOPED_TRACE(n);
                const label t = threadTeam::rank(), nT = threadTeam::size();
                // Block t starts where the t earlier ones end: sizes differ
                // by at most one, the larger first
                const label size = n/nT, extra = n % nT;
                EXPECT_EQ(b, 7 + t*size + std::min(t, extra));
                EXPECT_EQ(e - b, size + (t < extra ? 1 : 0));
            }
        }
        label b, e;
        threadBlock(7, 7 + n, b, e);
        EXPECT_EQ(b, 7);
        EXPECT_EQ(e, 7 + n);
    }
}


TEST(ParallelLoop, threadTeamSyncPublishesEachPassToTheNext)
{
    // Each pass sets a[i] from b of the neighbours, which other threads
    // wrote in the pass before; the serial loop's result must come out of
    // any team size, over many passes (a missing or leaky sync shows as a
    // stale neighbour)
    const label n = 1000, passes = 200;
    const auto run = [&](const int threads)
    {
        std::vector<double> a(n), b(n);
        std::iota(a.begin(), a.end(), 0.0);
        threadTeam team;
        #pragma omp parallel num_threads(threads) if(threads > 1)
        for (label p = 0; p < passes; ++p)
        {
            label lo, hi;
            threadBlock(0, n, lo, hi);
            for (label i = lo; i < hi; ++i)
            {
                b[i] = 0.5*a[i] + 0.25*(a[(i + 1) % n] + a[(i + n - 1) % n]) + 1;
            }
            team.sync();
            for (label i = lo; i < hi; ++i) a[i] = b[(i + 7) % n];
            team.sync();
        }
        return a;
    };
    const std::vector<double> one = run(1);
    for (const int threads : {2, 3})
    {
        const std::vector<double> many = run(threads);
        for (label i = 0; i < n; ++i)
        {
            ASSERT_EQ(many[i], one[i]) << threads << " threads, item " << i;
        }
    }
}


TEST(ParallelLoop, helpersInsideATeamOpenNoRegionOfTheirOwn)
{
    // Above minParallelLoop, but called by each thread of a team on its
    // own share: the loop stays on the calling thread
    const label n = 2*minParallelLoop + 3;
    int nested = 0, teams = 0;
    #pragma omp parallel num_threads(2) reduction(+: nested, teams)
    {
        teams += threadTeam::size() == 2;
        const int outer = threadTeam::rank();
        parallelFor(0, n, [&](const label)
        {
            nested += omp_get_active_level() != 1;
        });
        const bool sameThread = parallelAll(0, n, [&](const label)
        {
            return threadTeam::rank() == outer;
        });
        nested += !sameThread;
    }
    EXPECT_EQ(teams, 2);
    EXPECT_EQ(nested, 0);
}

TEST(ParallelLoop, teamOrOneRunsTheFasterAndTriesTheOtherNowAndThen)
{
    teamOrOne choice;
    // Each mode tried first: one thread, then the team
    EXPECT_FALSE(choice.chooseTeam());
    choice.record(2e-3, 100);           // 20 us an item
    EXPECT_TRUE(choice.chooseTeam());
    choice.record(1e-3, 100);           // 10 us an item
    EXPECT_DOUBLE_EQ(choice.cost(false), 2e-5);
    EXPECT_DOUBLE_EQ(choice.cost(true), 1e-5);
    // The team from now on, but for one trial of one thread per
    // trialEvery calls
    label teamCalls = 0, oneCalls = 0;
    for (label call = 0; call < 4*teamOrOne::trialEvery; ++call)
    {
        const bool team = choice.chooseTeam();
        (team ? teamCalls : oneCalls) += 1;
        choice.record(team ? 1e-3 : 2e-3, 100);
    }
    EXPECT_EQ(oneCalls, 4);
    EXPECT_EQ(teamCalls, 4*teamOrOne::trialEvery - 4);
    // The machine changes: the team becomes slower than one thread. The
    // team's mean follows its calls; once it is above one thread's, one
    // thread runs, and the team's trials keep finding it slow
    label callsToSwitch = 0;
    while (choice.chooseTeam())
    {
        choice.record(4e-3, 100);
        ASSERT_LT(++callsToSwitch, 20) << "never left the slow team";
    }
    choice.record(2e-3, 100);
    EXPECT_GT(choice.cost(true), choice.cost(false));
    // 10 -> 17.5 -> 23.1 us a sub-step: above one thread's 20 after two
    EXPECT_EQ(callsToSwitch, 2);
    label teamTrials = 0;
    for (label call = 0; call < 2*teamOrOne::trialEvery; ++call)
    {
        const bool team = choice.chooseTeam();
        teamTrials += team;
        choice.record(team ? 4e-3 : 2e-3, 100);
    }
    EXPECT_EQ(teamTrials, 2);
}

// ************************************************************************* //
