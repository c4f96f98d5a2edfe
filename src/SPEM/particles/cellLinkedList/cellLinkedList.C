#include "cellLinkedList.H"
#include "parallelLoop.H"
#include "error.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using Foam::label;
using Foam::scalar;

//- Loops shorter than this run on one thread (core/parallelLoop)
using Foam::minParallelLoop;

//- Relative enlargement of the cell size: a pair closer than the requested
//  size then always lies in adjacent cells, whatever the rounding of the
//  cell indices (a few ulp of the index, below 1e-11 for 1e5 cells a row)
constexpr scalar cellSizeMargin = 1e-9;

//- Resize, growing the capacity with slack when it must grow, so that
//  small changes of the size from step to step do not reallocate
template<class Type>
void resizeWithSlack(std::vector<Type>& v, const std::size_t n)
{
    if (n > v.capacity())
    {
        v.reserve(n + n/4 + 16);
    }
    v.resize(n);
}

template<class Type>
std::size_t capacityBytes(const std::vector<Type>& v)
{
    return v.capacity()*sizeof(Type);
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

std::string Foam::cellLinkedList::nonFiniteMessage
(
    const particleSet& particles
) const
{
    const std::vector<scalar>& x = particles.positions();
    for (label i = 0; i < particles.size(); ++i)
    {
        if (!std::isfinite(x[2*i]) || !std::isfinite(x[2*i + 1]))
        {
            std::ostringstream os;
            os  << "Particle " << i << " (id " << particles.id()[i]
                << ") has a non-finite position (" << x[2*i] << ' '
                << x[2*i + 1] << "): the neighbour search cannot place it"
                << " in a cell. The time step is probably unstable.";
            return os.str();
        }
    }
    return "a particle has a non-finite position";
}


std::string Foam::cellLinkedList::farParticleMessage
(
    const particleSet& particles,
    const scalar nCells,
    const scalar maxCells
) const
{
    // The particle farthest from the component-wise median position: a
    // lone particle that flew away moves the bounding box, not the median
    const label n = particles.size();
    const std::vector<scalar>& x = particles.positions();
    std::vector<scalar> coord(n);
    scalar median[2];
    for (label d = 0; d < 2; ++d)
    {
        for (label i = 0; i < n; ++i) coord[i] = x[2*i + d];
        std::nth_element(coord.begin(), coord.begin() + n/2, coord.end());
        median[d] = coord[n/2];
    }
    label far = 0;
    scalar farDist = -1;
    for (label i = 0; i < n; ++i)
    {
        const scalar d = std::hypot(x[2*i] - median[0], x[2*i + 1] - median[1]);
        if (d > farDist)
        {
            far = i;
            farDist = d;
        }
    }

    std::ostringstream os;
    os  << "Particle " << far << " (id " << particles.id()[far]
        << ") at (" << x[2*far] << ' ' << x[2*far + 1] << ") with velocity ("
        << particles.velocities()[2*far] << ' '
        << particles.velocities()[2*far + 1] << ") has flown away:"
        << " it is " << farDist << " m from the median particle position ("
        << median[0] << ' ' << median[1] << ") and the grid of cells of size "
        << levels_[0].cellSize << " over the bounding box of the " << n
        << " particles would need " << nCells << " cells, more than the"
        << " limit of " << maxCells << " (" << maxCellsPerParticle_
        << " per particle + " << extraCells_ << "). The time step is"
        << " probably unstable or the particle escaped through a wall.";
    return os.str();
}


void Foam::cellLinkedList::checkSupport
(
    const particleSet& particles,
    const scalar kappa
) const
{
    if (particles.size() != nParticles_)
    {
        FatalErrorInFunction
            << "The cell list was built for " << nParticles_
            << " particles, the set has " << particles.size()
            << ": call update() first" << exit(FatalError);
    }
    // The finer levels' cells are in proportion to their largest h
    if (kappa*hMax_ > levels_[0].cellSize)
    {
        FatalErrorInFunction
            << "Cells of size " << levels_[0].cellSize << " cannot hold every"
            << " neighbour for support radius kappa max(h) = " << kappa
            << " x " << hMax_ << " = " << kappa*hMax_
            << ": update() with a cell size >= kappa max(h)"
            << exit(FatalError);
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::cellLinkedList::cellLinkedList
(
    const label maxCellsPerParticle,
    const label extraCells,
    const label levelLimit
)
:
    maxCellsPerParticle_(maxCellsPerParticle),
    extraCells_(extraCells),
    levelLimit_(std::max(label(1), std::min(levelLimit, maxLevels))),
    nParticles_(0),
    nCells_(1),
    hMax_(0),
    cellStart_(2, 0)
{
    levels_.reserve(maxLevels);
    levels_.push_back(levelGrid{0, 0, 1, 1, 1, 1, 0, 0});
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::cellLinkedList::update
(
    const particleSet& particles,
    const scalar cellSize
)
{
    if (!tryUpdate(particles, cellSize))
    {
        FatalErrorInFunction
            << "The neighbour search failed: " << failure_.c_str()
            << exit(FatalError);
    }
}


bool Foam::cellLinkedList::tryUpdate
(
    const particleSet& particles,
    const scalar cellSize
)
{
    failure_.clear();
    if (!(cellSize > 0) || !std::isfinite(cellSize))
    {
        FatalErrorInFunction
            << "Cell size " << cellSize << " is not a positive number"
            << exit(FatalError);
    }

    if (!sizeGrid(particles, cellSize)) return false;

    const label n = particles.size();
    resizeWithSlack(cellStart_, nCells_ + 1);
    resizeWithSlack(cellParticles_, n);
    resizeWithSlack(particleCell_, n);

    assignCells(particles);
    sortByCell(n);

    nParticles_ = n;
    return true;
}


bool Foam::cellLinkedList::sizeGrid
(
    const particleSet& particles,
    const scalar cellSize
)
{
    const label n = particles.size();
    const scalar* __restrict__ x = particles.positions().data();
    const scalar* __restrict__ h = particles.smoothingLength().data();

    // Bounding box and the range of h; non-finite positions are counted,
    // not reported here (no exception may leave a parallel region)
    constexpr scalar big = std::numeric_limits<scalar>::max();
    scalar xMin = big, yMin = big, xMax = -big, yMax = -big, hMax = 0;
    scalar hMin = big;
    label nNonFinite = 0;
    #pragma omp parallel for schedule(static) reduction(min: xMin, yMin, hMin) reduction(max: xMax, yMax, hMax) reduction(+: nNonFinite) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        const scalar xi = x[2*i], yi = x[2*i + 1];
        if (!std::isfinite(xi) || !std::isfinite(yi))
        {
            ++nNonFinite;
            continue;
        }
        xMin = std::min(xMin, xi);
        xMax = std::max(xMax, xi);
        yMin = std::min(yMin, yi);
        yMax = std::max(yMax, yi);
        hMax = std::max(hMax, h[i]);
        // The finest positive h (a particle of h <= 0, which reaches
        // others only by their h, goes with the coarsest)
        if (h[i] > 0) hMin = std::min(hMin, h[i]);
    }

    nParticles_ = 0;
    if (nNonFinite > 0)
    {
        failure_ = nonFiniteMessage(particles);
        return false;
    }
    if (n == 0)
    {
        xMin = xMax = yMin = yMax = 0;
    }
    hMax_ = hMax;

    // Several levels only where the smoothing lengths differ by more than
    // a factor 2
    if
    (
        levelLimit_ > 1 && n > 0 && hMax > 0 && hMin <= 0.5*hMax
     && sizeLevels(particles, cellSize, hMin)
    )
    {
        return failure_.empty();
    }
    particleLevel_.clear();

    levelGrid g;
    g.cellSize = cellSize*(1 + cellSizeMargin);
    g.invCellSize = 1/g.cellSize;

    // Cell counts in floating point first: a far particle must not
    // overflow the integer count. An index is floor((x - x0)/cellSize), so
    // the particle at the upper bound is in the last cell.
    const scalar nxReal = std::floor((xMax - xMin)*g.invCellSize) + 1;
    const scalar nyReal = std::floor((yMax - yMin)*g.invCellSize) + 1;
    const scalar maxCells =
        scalar(maxCellsPerParticle_)*n + scalar(extraCells_);
    if (!(nxReal*nyReal <= maxCells))
    {
        levels_.resize(1);
        levels_[0].cellSize = g.cellSize;
        failure_ = farParticleMessage(particles, nxReal*nyReal, maxCells);
        return false;
    }

    g.x0 = xMin;
    g.y0 = yMin;
    g.nx = label(nxReal);
    g.ny = label(nyReal);
    g.cellBase = 0;
    g.hMax = hMax;
    levels_.resize(1);
    levels_[0] = g;
    nCells_ = g.nx*g.ny;
    return true;
}


bool Foam::cellLinkedList::sizeLevels
(
    const particleSet& particles,
    const scalar cellSize,
    const scalar hMin
)
{
    const label n = particles.size();
    const scalar* __restrict__ x = particles.positions().data();
    const scalar* __restrict__ h = particles.smoothingLength().data();
    const scalar hMax = hMax_;

    // Level of each particle: max(h)/2^(l+1) < h <= max(h)/2^l (exact: a
    // power of 2 scales without rounding)
    const label nLevels = std::min
    (
        levelLimit_, label(std::floor(std::log2(hMax/hMin))) + 1
    );
    const auto levelOf = [nLevels, hMax](const scalar hi)
    {
        if (!(hi > 0)) return label(0);
        label l = 0;
        for (scalar bound = 0.5*hMax; l < nLevels - 1 && hi <= bound; ++l)
        {
            bound *= 0.5;
        }
        return l;
    };
    constexpr scalar big = std::numeric_limits<scalar>::max();
    scalar box[maxLevels][4];
    scalar hLevel[maxLevels];
    label count[maxLevels];
    for (label l = 0; l < maxLevels; ++l)
    {
        box[l][0] = box[l][1] = big;
        box[l][2] = box[l][3] = -big;
        hLevel[l] = 0;
        count[l] = 0;
    }
    // One serial pass for the grids (a few operations a particle, only for
    // mixed sizes); the levels are stored once the grids are accepted
    for (label i = 0; i < n; ++i)
    {
        const label l = levelOf(h[i]);
        scalar* b = box[l];
        b[0] = std::min(b[0], x[2*i]);
        b[1] = std::min(b[1], x[2*i + 1]);
        b[2] = std::max(b[2], x[2*i]);
        b[3] = std::max(b[3], x[2*i + 1]);
        hLevel[l] = std::max(hLevel[l], h[i]);
        ++count[l];
    }

    // The levels present, coarsest first, numbered without gaps
    unsigned char present[maxLevels];
    label nPresent = 0;
    for (label l = 0; l < nLevels; ++l)
    {
        present[l] = static_cast<unsigned char>(nPresent);
        nPresent += count[l] > 0;
    }
    if (nPresent < 2) return false;   // one level after all: one grid

    const scalar maxCells =
        scalar(maxCellsPerParticle_)*n + scalar(extraCells_);
    scalar totalCells = 0;
    levels_.resize(nPresent);
    label base = 0;
    for (label l = 0; l < nLevels; ++l)
    {
        if (count[l] == 0) continue;
        levelGrid& g = levels_[present[l]];
        // In proportion to the level's largest h: at least kappa h_max,l
        // when the requested size is at least kappa max(h)
        g.cellSize = cellSize*(hLevel[l]/hMax)*(1 + cellSizeMargin);
        g.invCellSize = 1/g.cellSize;
        const scalar nxReal = std::floor((box[l][2] - box[l][0])*g.invCellSize) + 1;
        const scalar nyReal = std::floor((box[l][3] - box[l][1])*g.invCellSize) + 1;
        totalCells += nxReal*nyReal;
        if (!(totalCells <= maxCells))
        {
            levels_.resize(1);
            levels_[0].cellSize = cellSize*(1 + cellSizeMargin);
            particleLevel_.clear();
            failure_ = farParticleMessage(particles, totalCells, maxCells);
            return true;   // sized, and failed: failure_ says why
        }
        g.x0 = box[l][0];
        g.y0 = box[l][1];
        g.nx = label(nxReal);
        g.ny = label(nyReal);
        g.cellBase = base;
        g.hMax = hLevel[l];
        base += g.nx*g.ny;
    }
    resizeWithSlack(particleLevel_, n);
    unsigned char* __restrict__ level = particleLevel_.data();
    #pragma omp parallel for schedule(static) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i) level[i] = present[levelOf(h[i])];
    nCells_ = base;
    return true;
}


void Foam::cellLinkedList::assignCells(const particleSet& particles)
{
    const label n = particles.size();
    const scalar* __restrict__ x = particles.positions().data();

    label* __restrict__ cell = particleCell_.data();
    if (particleLevel_.empty())
    {
        const levelGrid& g = levels_[0];
        const scalar x0 = g.x0, y0 = g.y0, inv = g.invCellSize;
        const label nx = g.nx, ny = g.ny;
        #pragma omp parallel for schedule(static) if(n > minParallelLoop)
        for (label i = 0; i < n; ++i)
        {
            const label ix = std::min(label((x[2*i] - x0)*inv), nx - 1);
            const label iy = std::min(label((x[2*i + 1] - y0)*inv), ny - 1);
            cell[i] = iy*nx + ix;
        }
        return;
    }

    const unsigned char* __restrict__ level = particleLevel_.data();
    const levelGrid* __restrict__ grids = levels_.data();
    #pragma omp parallel for schedule(static) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        const levelGrid& g = grids[level[i]];
        const label ix =
            std::min(label((x[2*i] - g.x0)*g.invCellSize), g.nx - 1);
        const label iy =
            std::min(label((x[2*i + 1] - g.y0)*g.invCellSize), g.ny - 1);
        cell[i] = g.cellBase + iy*g.nx + ix;
    }
}


void Foam::cellLinkedList::sortByCell(const label n)
{
    const label nCells = nCells_;
    const label* __restrict__ cell = particleCell_.data();

    // Counting sort (stable, serial: O(N) increments, a few per cent of a
    // neighbour search). The counts go to start[c + 1]; after the prefix
    // sum start[c] is the first slot of cell c and serves as the fill
    // cursor, which leaves it at the first slot of c + 1: one shift back
    // restores the offsets without a second array.
    label* __restrict__ start = cellStart_.data();
    label* __restrict__ sorted = cellParticles_.data();
    std::fill(cellStart_.begin(), cellStart_.end(), 0);
    for (label i = 0; i < n; ++i)
    {
        ++start[cell[i] + 1];
    }
    for (label c = 0; c < nCells; ++c)
    {
        start[c + 1] += start[c];
    }
    for (label i = 0; i < n; ++i)
    {
        sorted[start[cell[i]]++] = i;
    }
    for (label c = nCells; c > 0; --c)
    {
        start[c] = start[c - 1];
    }
    start[0] = 0;
}


void Foam::cellLinkedList::particlesReordered()
{
    label* __restrict__ sorted = cellParticles_.data();
    label* __restrict__ cell = particleCell_.data();
    unsigned char* __restrict__ level =
        particleLevel_.empty() ? nullptr : particleLevel_.data();
    const label* __restrict__ start = cellStart_.data();
    for (label l = 0; l < label(levels_.size()); ++l)
    {
        const levelGrid& g = levels_[l];
        const label begin = g.cellBase, end = g.cellBase + g.nx*g.ny;
        #pragma omp parallel for schedule(static) if(end - begin > minParallelLoop)
        for (label c = begin; c < end; ++c)
        {
            for (label k = start[c]; k < start[c + 1]; ++k)
            {
                sorted[k] = k;
                cell[k] = c;
                if (level) level[k] = static_cast<unsigned char>(l);
            }
        }
    }
}


Foam::label Foam::cellLinkedList::nCandidates
(
    const particleSet& particles,
    const label i,
    const scalar kappa
) const
{
    const scalar* x = particles.positions().data();
    const scalar* h = particles.smoothingLength().data();
    label count = 0;
    for (label l = 0; l < label(levels_.size()); ++l)
    {
        label block[4];
        if (!neighbourBlock(x, h, i, l, kappa, block)) continue;
        const levelGrid& g = levels_[l];
        for (label iy = block[2]; iy <= block[3]; ++iy)
        {
            const label row = g.cellBase + iy*g.nx;
            count += cellStart_[row + block[1] + 1] - cellStart_[row + block[0]];
        }
    }
    return count;
}


void Foam::cellLinkedList::buildNeighbourLists
(
    const particleSet& particles,
    const scalar kappa,
    std::vector<label>& start,
    std::vector<label>& neighbours
) const
{
    checkSupport(particles, kappa);

    const label n = nParticles_;
    resizeWithSlack(start, n + 1);
    label* __restrict__ rowStart = start.data();
    rowStart[0] = 0;

    // Performance critical: the neighbour search of every particle, twice.
    // Pass 1 counts the neighbours of i into start[i + 1].
    #pragma omp parallel for schedule(static) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        label count = 0;
        forEachNeighbour
        (
            particles, i, kappa,
            [&count](label, scalar, scalar, scalar) { ++count; }
        );
        rowStart[i + 1] = count;
    }

    for (label i = 0; i < n; ++i)
    {
        rowStart[i + 1] += rowStart[i];
    }

    // Pass 2 writes each row at its offset: the rows and their order do not
    // depend on which thread computed them
    resizeWithSlack(neighbours, std::size_t(rowStart[n]));
    label* __restrict__ nbr = neighbours.data();
    #pragma omp parallel for schedule(static) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        label k = rowStart[i];
        forEachNeighbour
        (
            particles, i, kappa,
            [nbr, &k](label j, scalar, scalar, scalar) { nbr[k++] = j; }
        );
    }
}


std::size_t Foam::cellLinkedList::memoryBytes() const
{
    return
        capacityBytes(cellStart_) + capacityBytes(cellParticles_)
      + capacityBytes(particleCell_) + capacityBytes(particleLevel_)
      + capacityBytes(levels_);
}


// ************************************************************************* //
