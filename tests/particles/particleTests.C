/*---------------------------------------------------------------------------*\
Description
    Unit tests of the particle storage (particleSet) and the cell-linked-list
    neighbour search (cellLinkedList) of the particle half (paper sect.
    2.2): the search equals a brute-force search on random particles whose
    smoothing lengths differ by a factor of 4, its result does not depend on
    the number of threads, reordering by cell keeps each particle's data
    together, moved particles are searched again without reallocation, and
    a lost particle (NaN or far away) gives a clear error.

    ParticleNeighbourSearch.timingAt100kParticles prints the time of
    buildNeighbourLists on 1 and 2 threads (information, not asserted).

\*---------------------------------------------------------------------------*/

#include "cellLinkedList.H"
#include "error.H"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <string>

using namespace Foam;

namespace
{

//- Support factor of the kernel (WendlandC2)
constexpr scalar kappa = 2;

//- Random particles in [0, 1] x [0, 0.6]: half spread uniformly, half in a
//  dense cluster, with h = hMin 4^u, u uniform in [0, 1], plus a few pairs
//  at identical positions. hMin = 0.006 for 2000 particles, scaled with the
//  spacing for other counts. Every field is a function of the id so that a
//  permutation can be checked.
particleSet randomParticles(const label n, const unsigned seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<scalar> uni(0, 1);
    const scalar hMin = 0.006*std::sqrt(2000.0/n);

    particleSet ps;
    ps.reserve(n);
    for (label i = 0; i < n; ++i)
    {
        scalar x, y;
        if (i % 2 == 0)
        {
            x = uni(gen);
            y = 0.6*uni(gen);
        }
        else
        {
            x = 0.3 + 0.15*uni(gen);
            y = 0.2 + 0.1*uni(gen);
        }
        if (i % 97 == 1)
        {
            // Coincident with the previous particle
            x = ps.positions()[2*(i - 1)];
            y = ps.positions()[2*(i - 1) + 1];
        }
        const scalar h = hMin*std::pow(4.0, uni(gen));
        ps.append
        (
            x, y, i, -2.0*i, 1000 + i, 3.0*i, 1 + 0.5*i, h,
            particleSet::kind(i % 3), (unsigned char)(i % 5)
        );
    }
    return ps;
}

//- Sorted neighbours of every particle by testing every pair
std::vector<std::vector<label>> bruteForce
(
    const particleSet& ps,
    const scalar kappa
)
{
    const label n = ps.size();
    const std::vector<scalar>& x = ps.positions();
    const std::vector<scalar>& h = ps.smoothingLength();
    std::vector<std::vector<label>> nbr(n);
    for (label i = 0; i < n; ++i)
    {
        for (label j = 0; j < n; ++j)
        {
            const scalar dx = x[2*i] - x[2*j], dy = x[2*i + 1] - x[2*j + 1];
            const scalar hij = 0.5*(h[i] + h[j]);
            if (j != i && dx*dx + dy*dy < kappa*kappa*hij*hij)
            {
                nbr[i].push_back(j);
            }
        }
    }
    return nbr;
}

//- Neighbours of every particle from forEachNeighbour (sorted), checking
//  the separation it passes
std::vector<std::vector<label>> searchEach
(
    const cellLinkedList& cells,
    const particleSet& ps,
    const scalar kappa
)
{
    const std::vector<scalar>& x = ps.positions();
    std::vector<std::vector<label>> nbr(ps.size());
    for (label i = 0; i < ps.size(); ++i)
    {
        cells.forEachNeighbour
        (
            ps, i, kappa,
            [&](label j, scalar dx, scalar dy, scalar r)
            {
                nbr[i].push_back(j);
                EXPECT_EQ(dx, x[2*i] - x[2*j]);
                EXPECT_EQ(dy, x[2*i + 1] - x[2*j + 1]);
                EXPECT_NEAR(r, std::hypot(dx, dy), 1e-15);
            }
        );
        std::sort(nbr[i].begin(), nbr[i].end());
    }
    return nbr;
}

//- Compressed rows as sorted lists
std::vector<std::vector<label>> rows
(
    const std::vector<label>& start,
    const std::vector<label>& neighbours
)
{
    std::vector<std::vector<label>> nbr(start.size() - 1);
    for (size_t i = 0; i + 1 < start.size(); ++i)
    {
        nbr[i].assign(&neighbours[start[i]], &neighbours[start[i + 1]]);
        std::sort(nbr[i].begin(), nbr[i].end());
    }
    return nbr;
}

//- Expect equal neighbour lists, reporting the first differing particle
void expectSameNeighbours
(
    const std::vector<std::vector<label>>& a,
    const std::vector<std::vector<label>>& b,
    const std::string& what
)
{
    ASSERT_EQ(a.size(), b.size()) << what;
    for (size_t i = 0; i < a.size(); ++i)
    {
        ASSERT_EQ(a[i], b[i]) << what << ": particle " << i;
    }
}

//- The cell of particle k's position in the grid of its level, computed
//  independently from the grid data
label cellOf(const cellLinkedList& cells, const particleSet& ps, const label k)
{
    const cellLinkedList::levelGrid& g = cells.level(cells.levelOfParticle(k));
    const scalar x = ps.positions()[2*k], y = ps.positions()[2*k + 1];
    const label ix = std::min(label(std::floor((x - g.x0)/g.cellSize)), g.nx - 1);
    const label iy = std::min(label(std::floor((y - g.y0)/g.cellSize)), g.ny - 1);
    return g.cellBase + iy*g.nx + ix;
}

//- Restores the number of OpenMP threads at the end of a scope
struct threadCountGuard
{
    const int nThreads = omp_get_max_threads();
    ~threadCountGuard() { omp_set_num_threads(nThreads); }
};

} // End anonymous namespace


TEST(ParticleSet, appendResizeAndMemoryAccounting)
{
    particleSet ps(3);
    ASSERT_EQ(ps.size(), 3);
    EXPECT_EQ(ps.positions().size(), 6u);
    EXPECT_EQ(ps.id()[2], 2);
    EXPECT_EQ(ps.kinds()[1], particleSet::kind::fluid);

    const label i = ps.append
    (
        1, 2, 3, 4, 1000, 5, 0.1, 0.02, particleSet::kind::wall, 2
    );
    ASSERT_EQ(i, 3);
    ASSERT_EQ(ps.size(), 4);
    EXPECT_EQ(ps.positions()[7], 2);
    EXPECT_EQ(ps.velocities()[6], 3);
    EXPECT_EQ(ps.density()[3], 1000);
    EXPECT_EQ(ps.pressure()[3], 5);
    EXPECT_EQ(ps.mass()[3], 0.1);
    EXPECT_EQ(ps.smoothingLength()[3], 0.02);
    EXPECT_EQ(ps.kinds()[3], particleSet::kind::wall);
    EXPECT_EQ(ps.level()[3], 2);
    EXPECT_EQ(ps.id()[3], 3);
    EXPECT_EQ(ps.maxSmoothingLength(), 0.02);

    ps.resize(2);
    EXPECT_EQ(ps.size(), 2);
    EXPECT_EQ(ps.velocities().size(), 4u);
    EXPECT_GE(ps.memoryBytes(), 2*particleSet::fieldBytesPerParticle);
    EXPECT_EQ(particleSet::fieldBytesPerParticle, 70u);
}


TEST(ParticleSet, reorderBySortOrderKeepsEachParticlesDataTogether)
{
    const label n = 2000;
    particleSet ps = randomParticles(n, 7);
    const particleSet original = ps;

    cellLinkedList cells;
    cells.update(ps, kappa*ps.maxSmoothingLength());
    const std::vector<label> order = cells.sortOrder();
    ASSERT_EQ(label(order.size()), n);
    ps.reorder(order);
    cells.particlesReordered();

    // Every field of the particle at i is the one of particle order[i]
    std::vector<bool> seen(n, false);
    for (label i = 0; i < n; ++i)
    {
        const label id = ps.id()[i];
        ASSERT_EQ(id, order[i]) << "particle " << i;
        ASSERT_FALSE(seen[id]);
        seen[id] = true;
        for (label d = 0; d < 2; ++d)
        {
            ASSERT_EQ(ps.positions()[2*i + d], original.positions()[2*id + d]);
            ASSERT_EQ(ps.velocities()[2*i + d], original.velocities()[2*id + d]);
        }
        ASSERT_EQ(ps.velocities()[2*i], id);
        ASSERT_EQ(ps.density()[i], 1000 + id);
        ASSERT_EQ(ps.pressure()[i], 3.0*id);
        ASSERT_EQ(ps.mass()[i], 1 + 0.5*id);
        ASSERT_EQ(ps.smoothingLength()[i], original.smoothingLength()[id]);
        ASSERT_EQ(ps.kinds()[i], particleSet::kind(id % 3));
        ASSERT_EQ(ps.level()[i], id % 5);
    }
    label nMoved = 0;
    for (label i = 0; i < n; ++i) nMoved += order[i] != i;
    EXPECT_GT(nMoved, n/2) << "the random set was already nearly sorted";

    // The particles of each cell are now contiguous: cellStart ranges hold
    // particles of that cell, in index order
    const std::vector<label>& start = cells.cellStart();
    label nonEmpty = 0;
    for (label c = 0; c < cells.nCells(); ++c)
    {
        nonEmpty += start[c + 1] > start[c];
        for (label k = start[c]; k < start[c + 1]; ++k)
        {
            ASSERT_EQ(cells.cellParticles()[k], k);
            ASSERT_EQ(cells.cellOfParticle(k), c);
            ASSERT_EQ(cellOf(cells, ps, k), c) << "particle " << k;
        }
    }
    EXPECT_GT(nonEmpty, 10);

    // A fresh update of the sorted set agrees: the sort order is the identity
    cellLinkedList fresh;
    fresh.update(ps, kappa*ps.maxSmoothingLength());
    EXPECT_EQ(fresh.cellStart(), cells.cellStart());
    for (label i = 0; i < n; ++i)
    {
        ASSERT_EQ(fresh.sortOrder()[i], i);
    }

    // The search on the reordered set still equals brute force
    expectSameNeighbours
    (
        searchEach(cells, ps, kappa), bruteForce(ps, kappa), "after reorder"
    );

    // A second reorder allocates nothing, and a caller's field follows
    const std::size_t bytes = ps.memoryBytes();
    std::vector<scalar> extra(2*n);
    for (label i = 0; i < n; ++i)
    {
        extra[2*i] = ps.id()[i];
        extra[2*i + 1] = -ps.id()[i];
    }
    std::vector<label> reverse(n);
    for (label i = 0; i < n; ++i) reverse[i] = n - 1 - i;
    ps.reorderField(reverse, 2, extra);
    ps.reorder(reverse);
    EXPECT_EQ(ps.memoryBytes(), bytes);
    for (label i = 0; i < n; ++i)
    {
        ASSERT_EQ(extra[2*i], ps.id()[i]);
        ASSERT_EQ(extra[2*i + 1], -ps.id()[i]);
    }
}


TEST(ParticleNeighbourSearch, equalsBruteForceForParticlesOfMixedSize)
{
    const label n = 2000;
    const particleSet ps = randomParticles(n, 12345);
    const std::vector<scalar>& h = ps.smoothingLength();
    const scalar hMax = ps.maxSmoothingLength();
    const scalar hMin = *std::min_element(h.begin(), h.end());
    ASSERT_GT(hMax/hMin, 3.5);

    cellLinkedList cells;
    cells.update(ps, kappa*hMax);
    EXPECT_GT(cells.nCells(), 50) << "the grid must have many cells";

    const std::vector<std::vector<label>> exact = bruteForce(ps, kappa);
    expectSameNeighbours(searchEach(cells, ps, kappa), exact, "forEachNeighbour");

    std::vector<label> start, neighbours;
    cells.buildNeighbourLists(ps, kappa, start, neighbours);
    ASSERT_EQ(label(start.size()), n + 1);
    expectSameNeighbours(rows(start, neighbours), exact, "buildNeighbourLists");

    // Symmetric (h_ij = h_ji), and the set is not trivial: pairs of very
    // different h and particles with many neighbours
    label nPairs = 0, nMixedPairs = 0;
    size_t maxCount = 0;
    for (label i = 0; i < n; ++i)
    {
        const std::vector<label>& ni = exact[i];
        maxCount = std::max(maxCount, ni.size());
        for (const label j : ni)
        {
            ASSERT_TRUE(std::binary_search(exact[j].begin(), exact[j].end(), i))
                << i << " sees " << j << " but not conversely";
            ++nPairs;
            nMixedPairs += std::max(h[i], h[j]) > 2.5*std::min(h[i], h[j]);
        }
    }
    std::cout << "mean neighbours " << scalar(nPairs)/n << ", max " << maxCount
        << ", pairs with h ratio > 2.5: " << nMixedPairs/2 << std::endl;
    EXPECT_GT(nPairs, 10*n);
    EXPECT_GT(nMixedPairs, n);

    // With a smaller support the search still agrees (cells larger than
    // needed are fine)
    expectSameNeighbours
    (
        searchEach(cells, ps, 1.3), bruteForce(ps, 1.3), "kappa 1.3"
    );
}


TEST(ParticleNeighbourSearch, finerParticlesScanCellsOfTheirOwnSize)
{
    // Coarse particles (spacing d, h = 1.3 d) beside fine ones (d/4) and a
    // strip of medium ones (d/2) between them, each lattice jittered by a
    // tenth of its spacing: a refined region beside coarse particles, as
    // in multi-resolution SPEM or on a graded mesh
    const scalar d = 0.04;
    particleSet ps(0);
    std::mt19937 gen(17);
    std::uniform_real_distribution<scalar> jitter(-0.1, 0.1);
    const auto lattice = [&](scalar x0, scalar x1, scalar y1, scalar dx)
    {
        for (scalar y = 0.5*dx; y < y1; y += dx)
        {
            for (scalar x = x0 + 0.5*dx; x < x1; x += dx)
            {
                ps.append
                (
                    x + dx*jitter(gen), y + dx*jitter(gen), 0, 0, 1000, 0,
                    1000*dx*dx, 1.3*dx, particleSet::kind::fluid, 0
                );
            }
        }
    };
    lattice(0, 0.6, 0.5, d);
    lattice(0.6, 0.7, 0.5, d/2);
    lattice(0.7, 1.0, 0.5, d/4);
    // and a patch 64 times finer among the coarse ones (levels 3-5
    // empty): a coarse particle scans some 130 of its rows, more than
    // one batch of forEachNeighbour
    for (label k = 0; k < 256; ++k)
    {
        const scalar dx = d/64;
        ps.append
        (
            0.3 + dx*(k % 16 + 0.5 + jitter(gen)),
            0.2 + dx*(k/16 + 0.5 + jitter(gen)), 0, 0, 1000, 0,
            1000*dx*dx, 1.3*dx, particleSet::kind::fluid, 0
        );
    }
    // and a particle of h = 0, which reaches others only by their h: it
    // goes with the coarsest level
    ps.append(0.805, 0.255, 0, 0, 1000, 0, 0.01, 0, particleSet::kind::fluid, 0);
    const label n = ps.size();

    cellLinkedList cells, single(cellLinkedList::defaultMaxCellsPerParticle,
        cellLinkedList::defaultExtraCells, 1);
    cells.update(ps, kappa*ps.maxSmoothingLength());
    single.update(ps, kappa*ps.maxSmoothingLength());
    ASSERT_EQ(cells.nLevels(), 4);
    ASSERT_EQ(single.nLevels(), 1);
    for (label l = 0; l < 4; ++l)
    {
        EXPECT_NEAR
        (
            cells.level(l).cellSize, kappa*1.3*d/(l < 3 ? 1 << l : 64), 1e-9
        ) << "level " << l;
    }

    // Every neighbour is found, from every level, and the sort order is a
    // permutation that keeps the search right
    const std::vector<std::vector<label>> exact = bruteForce(ps, kappa);
    expectSameNeighbours(searchEach(cells, ps, kappa), exact, "levels");
    expectSameNeighbours(searchEach(single, ps, kappa), exact, "one grid");
    std::vector<label> start, neighbours;
    cells.buildNeighbourLists(ps, kappa, start, neighbours);
    expectSameNeighbours(rows(start, neighbours), exact, "neighbour lists");
    particleSet sorted = ps;
    sorted.reorder(cells.sortOrder());
    cells.particlesReordered();
    expectSameNeighbours
    (
        searchEach(cells, sorted, kappa), bruteForce(sorted, kappa),
        "after the reorder"
    );
    for (label k = 0; k < n; ++k)
    {
        // h = 1.3 d, 1.3 d/2, 1.3 d/4, 1.3 d/64: levels 0, 1, 2, 3; h = 0:
        // level 0
        const scalar hk = sorted.smoothingLength()[k];
        ASSERT_EQ
        (
            cells.levelOfParticle(k),
            hk > d || hk == 0 ? 0 : (hk > 0.5*d ? 1 : (hk > 0.1*d ? 2 : 3))
        ) << "particle " << k;
        ASSERT_EQ(cells.cellOfParticle(k), cellOf(cells, sorted, k))
            << "particle " << k;
    }

    // The point searches of the coupling: every particle in the support
    // of a point, and every particle within the pair reach of a point of
    // a coarser, equal or finer smoothing length
    const std::vector<scalar>& x = sorted.positions();
    const std::vector<scalar>& h = sorted.smoothingLength();
    std::uniform_real_distribution<scalar> ux(-0.1, 1.1), uy(-0.1, 0.6);
    for (label p = 0; p < 300; ++p)
    {
        const scalar px = ux(gen), py = uy(gen);
        for (const scalar hPoint : {0.3*d, 1.3*d, 4*d})
        {
            std::vector<label> found, foundNear, want, wantNear;
            cells.forEachParticleInReach
            (
                sorted, px, py, hPoint, kappa,
                [&](label j, scalar, scalar, scalar) { found.push_back(j); }
            );
            cells.forEachParticleNear
            (
                sorted, px, py, kappa,
                [&](label j, scalar, scalar, scalar) { foundNear.push_back(j); }
            );
            for (label j = 0; j < n; ++j)
            {
                const scalar r = std::hypot(px - x[2*j], py - x[2*j + 1]);
                if (r < 0.5*kappa*(hPoint + h[j])) want.push_back(j);
                if (r < kappa*h[j]) wantNear.push_back(j);
            }
            std::sort(found.begin(), found.end());
            std::sort(foundNear.begin(), foundNear.end());
            ASSERT_EQ(found, want) << "point " << p << ", h " << hPoint;
            ASSERT_EQ(foundNear, wantNear) << "point " << p;
        }
    }

    // What each particle tests: with one grid sized for the coarse h a
    // fine particle tests the fine particles of 3x3 cells of 2.6 d, up to
    // 16 x 61 = 970 of them (measured: 615 on average, the region being
    // narrow), for about 19 neighbours; in cells of its own size about 61
    // (measured: 60), and of the coarser levels the few within its reach
    scalar fine[2] = {0, 0}, all[2] = {0, 0};
    label nFine = 0, nNeighbours = 0;
    for (label i = 0; i < n; ++i)
    {
        const label byLevels = cells.nCandidates(sorted, i, kappa);
        const label oneGrid = single.nCandidates(ps, i, kappa);
        all[0] += byLevels;
        all[1] += oneGrid;
        const scalar hOne = ps.smoothingLength()[i];
        const scalar hLevels = sorted.smoothingLength()[i];
        if (hOne < 0.5*d && hOne > 0.1*d)
        {
            fine[1] += oneGrid;
            ++nFine;
        }
        if (hLevels < 0.5*d && hLevels > 0.1*d)
        {
            fine[0] += byLevels;
            nNeighbours += label(exact[sorted.id()[i]].size());
        }
    }
    std::printf
    (
        "%d particles, %d fine: a fine particle tests %.0f particles in the"
        " levels' cells, %.0f in one grid, for %.1f neighbours; all"
        " particles %.0f and %.0f\n",
        n, nFine, fine[0]/nFine, fine[1]/nFine, scalar(nNeighbours)/nFine,
        all[0]/n, all[1]/n
    );
    EXPECT_LT(fine[0], 0.25*fine[1]);
    EXPECT_LT(fine[0]/nFine, 5*scalar(nNeighbours)/nFine);
    EXPECT_LT(all[0], 0.5*all[1]);
}


TEST(ParticleNeighbourSearch, anUnmarkedBlockMeansNoMarkedNeighbour)
{
    // Mixed smoothing lengths (several levels) and the cells of some
    // particles marked (those of one kind and of the finest level in the
    // dense cluster, as refined fluid among coarser walls): a particle
    // whose blocks hold no marked cell has no marked particle among its
    // neighbours (sphFluid::wallPass skips its search on that), also when
    // the marked ones are of another level, and the answer is not always
    // "marked"
    const particleSet ps = randomParticles(2000, 29);
    const label n = ps.size();
    cellLinkedList cells;
    cells.update(ps, kappa*ps.maxSmoothingLength());
    const label finest = cells.nLevels() - 1;
    ASSERT_GT(finest, 0);

    const std::vector<scalar>& x = ps.positions();
    std::vector<bool> marked(n, false);
    std::vector<unsigned char> mark(cells.nCells(), 0);
    for (label j = 0; j < n; ++j)
    {
        marked[j] =
            ps.kinds()[j] == particleSet::kind(0)
         && cells.levelOfParticle(j) == finest
         && x[2*j] > 0.3 && x[2*j] < 0.45 && x[2*j + 1] > 0.2
         && x[2*j + 1] < 0.3;
        if (marked[j]) mark[cells.cellOfParticle(j)] = 1;
    }

    const std::vector<std::vector<label>> exact = bruteForce(ps, kappa);
    label nUnmarked = 0, nWithMarkedNeighbour = 0, nOtherLevel = 0;
    for (label i = 0; i < n; ++i)
    {
        bool markedNeighbour = false;
        for (const label j : exact[i]) markedNeighbour |= marked[j];
        const bool around =
            cells.anyMarkedCellAround(ps, i, kappa, mark.data());
        if (markedNeighbour)
        {
            ++nWithMarkedNeighbour;
            nOtherLevel += cells.levelOfParticle(i) != finest;
            ASSERT_TRUE(around) << "particle " << i;
        }
        nUnmarked += !around;
    }
    std::printf
    (
        "%d particles, %d levels: %d with a marked neighbour (%d of them on"
        " a coarser level), %d with no marked cell around\n",
        n, finest + 1, nWithMarkedNeighbour, nOtherLevel, nUnmarked
    );
    EXPECT_GT(nOtherLevel, 0);
    EXPECT_GT(nUnmarked, n/4);
}


TEST(ParticleNeighbourSearch, resultsIndependentOfThreadCount)
{
    threadCountGuard guard;

    // More particles than minParallelLoop, so that the loops do run on
    // several threads
    const label n = 20000;
    particleSet ps = randomParticles(n, 99);
    const scalar cellSize = kappa*ps.maxSmoothingLength();

    std::vector<label> start[2], neighbours[2], order[2];
    for (int t = 0; t < 2; ++t)
    {
        omp_set_num_threads(t + 1);
        ASSERT_EQ(omp_get_max_threads(), t + 1);
        cellLinkedList cells;
        cells.update(ps, cellSize);
        order[t] = cells.sortOrder();
        cells.buildNeighbourLists(ps, kappa, start[t], neighbours[t]);
    }
    EXPECT_EQ(order[0], order[1]);
    EXPECT_EQ(start[0], start[1]);
    EXPECT_EQ(neighbours[0], neighbours[1]);
    EXPECT_GT(neighbours[0].size(), size_t(10*n));

    // and after a reorder on 2 threads the particles match a 1-thread one
    particleSet copy = ps;
    omp_set_num_threads(1);
    copy.reorder(order[0]);
    omp_set_num_threads(2);
    ps.reorder(order[0]);
    EXPECT_EQ(ps.positions(), copy.positions());
    EXPECT_EQ(ps.id(), copy.id());
}


TEST(ParticleNeighbourSearch, updateOfMovedParticlesIsCorrectWithoutReallocation)
{
    const label n = 2000;
    particleSet ps = randomParticles(n, 2024);
    const scalar hMin = 0.006;

    cellLinkedList cells;
    cells.update(ps, kappa*ps.maxSmoothingLength());
    ps.reorder(cells.sortOrder());
    cells.particlesReordered();
    std::vector<label> start, neighbours;
    cells.buildNeighbourLists(ps, kappa, start, neighbours);

    const std::size_t cellBytes = cells.memoryBytes();
    const std::size_t setBytes = ps.memoryBytes();
    const std::size_t startCapacity = start.capacity();
    const std::size_t neighbourCapacity = neighbours.capacity();
    const label* neighbourData = neighbours.data();

    std::mt19937 gen(5);
    std::uniform_real_distribution<scalar> shift(-0.3*hMin, 0.3*hMin);
    for (int step = 0; step < 5; ++step)
    {
        for (scalar& x : ps.positions()) x += shift(gen);

        cells.update(ps, kappa*ps.maxSmoothingLength());
        ps.reorder(cells.sortOrder());
        cells.particlesReordered();
        cells.buildNeighbourLists(ps, kappa, start, neighbours);

        const std::vector<std::vector<label>> exact = bruteForce(ps, kappa);
        expectSameNeighbours
        (
            searchEach(cells, ps, kappa), exact,
            "forEachNeighbour, step " + std::to_string(step)
        );
        expectSameNeighbours
        (
            rows(start, neighbours), exact,
            "buildNeighbourLists, step " + std::to_string(step)
        );

        EXPECT_EQ(cells.memoryBytes(), cellBytes) << "step " << step;
        EXPECT_EQ(ps.memoryBytes(), setBytes) << "step " << step;
        EXPECT_EQ(start.capacity(), startCapacity) << "step " << step;
        EXPECT_EQ(neighbours.capacity(), neighbourCapacity) << "step " << step;
        EXPECT_EQ(neighbours.data(), neighbourData) << "step " << step;
    }
}


class ParticleNeighbourSearchErrors : public ::testing::Test
{
protected:

    bool previous_ = false;

    void SetUp() override
    {
        previous_ = Foam::FatalError.throwExceptions();
    }

    void TearDown() override
    {
        Foam::FatalError.throwExceptions(previous_);
    }

    //- The message of the error raised by update(), empty if none
    static std::string updateError(cellLinkedList& cells, const particleSet& ps)
    {
        try
        {
            cells.update(ps, kappa*ps.maxSmoothingLength());
        }
        catch (const Foam::error& err)
        {
            return err.message();
        }
        return std::string();
    }
};


TEST_F(ParticleNeighbourSearchErrors, lostParticleGivesDocumentedError)
{
    const label n = 2000;
    cellLinkedList cells;
    const std::size_t emptyBytes = cells.memoryBytes();

    {
        particleSet ps = randomParticles(n, 3);
        ps.positions()[2*123] = std::numeric_limits<scalar>::quiet_NaN();
        const std::string msg = updateError(cells, ps);
        std::cout << "NaN:      " << msg << std::endl;
        EXPECT_NE(msg.find("Particle 123 (id 123)"), std::string::npos) << msg;
        EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;
    }
    {
        particleSet ps = randomParticles(n, 3);
        ps.positions()[2*45 + 1] = -std::numeric_limits<scalar>::infinity();
        const std::string msg = updateError(cells, ps);
        EXPECT_NE(msg.find("Particle 45 (id 45)"), std::string::npos) << msg;
        EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;
    }
    for (const scalar far : {1e300, -1e12, 1000.0})
    {
        particleSet ps = randomParticles(n, 3);
        ps.positions()[2*77] = far;
        const std::string msg = updateError(cells, ps);
        std::cout << "x = " << far << ": " << msg << std::endl;
        EXPECT_NE(msg.find("Particle 77 (id 77)"), std::string::npos) << msg;
        EXPECT_NE(msg.find("flown away"), std::string::npos) << msg;
    }
    // Nothing was allocated for the grids that were refused
    EXPECT_LT(cells.memoryBytes(), emptyBytes + 1024);

    // A particle further out but within the cell limit is searched normally
    {
        particleSet ps = randomParticles(n, 3);
        ps.positions()[2*77] = 2.0;
        EXPECT_EQ(updateError(cells, ps), "");
        expectSameNeighbours
        (
            searchEach(cells, ps, kappa), bruteForce(ps, kappa),
            "after recovering"
        );
    }

    // Cells smaller than the support are refused by the search
    {
        particleSet ps = randomParticles(n, 3);
        cells.update(ps, ps.maxSmoothingLength());
        std::vector<label> start, neighbours;
        std::string msg;
        try
        {
            cells.buildNeighbourLists(ps, kappa, start, neighbours);
        }
        catch (const Foam::error& err)
        {
            msg = err.message();
        }
        EXPECT_NE(msg.find("cannot hold every neighbour"), std::string::npos)
            << msg;
    }
}


TEST(ParticleNeighbourSearch, timingAt100kParticles)
{
    threadCountGuard guard;

    // A jittered lattice of spacing dx with h = 1.3 dx, sorted by cell: a
    // typical single-resolution fluid (about 21 neighbours per particle)
    const label nx = 400, ny = 250;
    const scalar dx = 0.01, h = 1.3*dx;
    std::mt19937 gen(1);
    std::uniform_real_distribution<scalar> jitter(-0.1*dx, 0.1*dx);
    particleSet ps;
    ps.reserve(nx*ny);
    for (label j = 0; j < ny; ++j)
    {
        for (label i = 0; i < nx; ++i)
        {
            ps.append
            (
                (i + 0.5)*dx + jitter(gen), (j + 0.5)*dx + jitter(gen),
                0, 0, 1000, 0, 1000*dx*dx, h
            );
        }
    }
    cellLinkedList cells;
    cells.update(ps, kappa*h);
    ps.reorder(cells.sortOrder());
    cells.particlesReordered();

    // Mean wall-clock time of a call over a few repetitions [ms]
    const auto time = [](auto&& f)
    {
        const int repeat = 20;
        f();
        const auto t0 = std::chrono::steady_clock::now();
        for (int r = 0; r < repeat; ++r) f();
        const auto t1 = std::chrono::steady_clock::now();
        return 1e3*std::chrono::duration<scalar>(t1 - t0).count()/repeat;
    };

    std::vector<label> start[2], neighbours[2];
    for (int t = 0; t < 2; ++t)
    {
        omp_set_num_threads(t + 1);
        const scalar tUpdate = time([&]{ cells.update(ps, kappa*h); });
        const scalar tReorder = time
        (
            [&]{ ps.reorder(cells.sortOrder()); cells.particlesReordered(); }
        );
        const scalar tLists = time
        (
            [&]{ cells.buildNeighbourLists(ps, kappa, start[t], neighbours[t]); }
        );
        std::cout << "N = " << ps.size() << ", " << (t + 1) << " thread(s): "
            << "buildNeighbourLists " << tLists << " ms, update " << tUpdate
            << " ms, reorder " << tReorder << " ms; "
            << scalar(neighbours[t].size())/ps.size()
            << " neighbours per particle; memory per particle: particles "
            << ps.memoryBytesPerParticle() << " B, cells "
            << scalar(cells.memoryBytes())/ps.size() << " B, lists "
            << scalar((start[t].capacity() + neighbours[t].capacity())*sizeof(label))/ps.size()
            << " B" << std::endl;
    }
    EXPECT_EQ(start[0], start[1]);
    EXPECT_EQ(neighbours[0], neighbours[1]);
}


// ************************************************************************* //
