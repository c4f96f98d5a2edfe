#include "elementLocator.H"

#include <cmath>
#include <cstdint>
#include <limits>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::elementLocator::elementLocator()
:
    version_(-1),
    nElements_(-1),
    margin_(0),
    coordinateScale_(0),
    gx0_(0),
    gy0_(0),
    cellSize_(1),
    invCellSize_(1),
    nx_(0),
    ny_(0),
    nBuilds_(0),
    nPasses_(0)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::elementLocator::drift
(
    const std::vector<scalar>& x,
    const label nElements,
    const label version
) const
{
    ++nPasses_;
    constexpr scalar never = std::numeric_limits<scalar>::infinity();
    if (version != version_ || nElements != nElements_) return never;
    if (x.size() != x0_.size()) return never;
    const scalar* a = x.data();
    const scalar* b = x0_.data();
    // A NaN compares false: counted apart, so that the loop vectorises
    scalar largest = 0;
    bool finite = true;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        const scalar d = std::abs(a[i] - b[i]);
        largest = d > largest ? d : largest;
        finite = finite & (d == d);
    }
    return finite ? largest : never;
}


bool Foam::elementLocator::build
(
    const std::vector<scalar>& x,
    const std::vector<label>& elementNodes,
    const label nElements,
    const label version
)
{
    ++nBuilds_;
    x0_ = x;
    version_ = version;
    nElements_ = nElements;
    cellStart_.assign(1, 0);
    cellElements_.clear();
    nx_ = ny_ = 0;
    if (nElements == 0) return true;

    // Bounding box of the elements' nodes and their mean size
    scalar lo[2] = {GREAT, GREAT}, hi[2] = {-GREAT, -GREAT};
    scalar sumArea = 0;
    for (label el = 0; el < nElements; ++el)
    {
        const label* n = &elementNodes[3*el];
        for (label a = 0; a < 3; ++a)
        {
            for (label c = 0; c < 2; ++c)
            {
                lo[c] = std::min(lo[c], x[2*n[a] + c]);
                hi[c] = std::max(hi[c], x[2*n[a] + c]);
            }
        }
        const scalar* p = &x[2*n[0]];
        const scalar* q = &x[2*n[1]];
        const scalar* r = &x[2*n[2]];
        sumArea += 0.5*std::abs
        (
            (q[0] - p[0])*(r[1] - p[1]) - (q[1] - p[1])*(r[0] - p[0])
        );
    }
    // Cells of about two elements' size, the boxes enlarged by half an
    // element: a few elements per cell, a rebuild every few steps where the
    // fastest node crosses half an element (the flow's Courant number
    // below 1 moves it by under an element per step)
    if (!std::isfinite(hi[0] - lo[0]) || !std::isfinite(hi[1] - lo[1]))
    {
        version_ = -1;      // never valid: the next query tries again
        return false;
    }
    const scalar size = std::sqrt(std::max(sumArea, VSMALL)/nElements);
    margin_ = 0.5*size;
    coordinateScale_ =
        std::max
        (
            std::max(std::abs(lo[0]), std::abs(hi[0])),
            std::max(std::abs(lo[1]), std::abs(hi[1]))
        )
      + reach();
    cellSize_ = 2*size;
    // At most about 4 cells per element, whatever the box's aspect
    const scalar w = hi[0] - lo[0] + 2*margin_, h = hi[1] - lo[1] + 2*margin_;
    while ((w/cellSize_ + 1)*(h/cellSize_ + 1) > 4.0*nElements + 16)
    {
        cellSize_ *= 2;
    }
    invCellSize_ = 1/cellSize_;
    gx0_ = lo[0] - margin_;
    gy0_ = lo[1] - margin_;
    nx_ = label(w*invCellSize_) + 1;
    ny_ = label(h*invCellSize_) + 1;

    // The cell range of each element's enlarged box; counting sort
    const auto cellRange =
        [&](const label el, label& i0, label& i1, label& j0, label& j1)
        {
            const label* n = &elementNodes[3*el];
            scalar l[2] = {GREAT, GREAT}, u[2] = {-GREAT, -GREAT};
            for (label a = 0; a < 3; ++a)
            {
                for (label c = 0; c < 2; ++c)
                {
                    l[c] = std::min(l[c], x[2*n[a] + c]);
                    u[c] = std::max(u[c], x[2*n[a] + c]);
                }
            }
            i0 = std::max<label>(0, label((l[0] - margin_ - gx0_)*invCellSize_));
            j0 = std::max<label>(0, label((l[1] - margin_ - gy0_)*invCellSize_));
            i1 = std::min<label>(nx_ - 1, label((u[0] + margin_ - gx0_)*invCellSize_));
            j1 = std::min<label>(ny_ - 1, label((u[1] + margin_ - gy0_)*invCellSize_));
        };
    cellStart_.assign(nx_*ny_ + 1, 0);
    for (label el = 0; el < nElements; ++el)
    {
        label i0, i1, j0, j1;
        cellRange(el, i0, i1, j0, j1);
        for (label j = j0; j <= j1; ++j)
        {
            for (label i = i0; i <= i1; ++i) ++cellStart_[j*nx_ + i + 1];
        }
    }
    for (label c = 0; c < nx_*ny_; ++c) cellStart_[c + 1] += cellStart_[c];
    cellElements_.resize(cellStart_.back());
    std::vector<label> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (label el = 0; el < nElements; ++el)
    {
        label i0, i1, j0, j1;
        cellRange(el, i0, i1, j0, j1);
        for (label j = j0; j <= j1; ++j)
        {
            for (label i = i0; i <= i1; ++i)
            {
                cellElements_[fill[j*nx_ + i]++] = el;
            }
        }
    }
    return true;
}


void Foam::elementLocator::renumber
(
    const std::vector<label>& oldToNew,
    const label nElements,
    const label versionBefore,
    const label version
)
{
    if (version_ != versionBefore || label(oldToNew.size()) != nElements_)
    {
        return;
    }
    // In place: a cell's kept elements move to the front of what is left,
    // in their order (increasing old numbers map to increasing new ones)
    label out = 0;
    label begin = cellStart_[0];
    for (std::size_t c = 0; c + 1 < cellStart_.size(); ++c)
    {
        const label end = cellStart_[c + 1];
        cellStart_[c] = out;
        for (label k = begin; k < end; ++k)
        {
            const label el = oldToNew[cellElements_[k]];
            if (el >= 0) cellElements_[out++] = el;
        }
        begin = end;
    }
    cellStart_.back() = out;
    cellElements_.resize(out);
    nElements_ = nElements;
    version_ = version;
}


bool Foam::elementLocator::contains
(
    const std::vector<scalar>& x,
    const label* n,
    const scalar px,
    const scalar py,
    scalar bary[3]
)
{
    const scalar* a = &x[2*n[0]];
    const scalar* b = &x[2*n[1]];
    const scalar* c = &x[2*n[2]];
    const scalar det =
        (b[0] - a[0])*(c[1] - a[1]) - (c[0] - a[0])*(b[1] - a[1]);
    const scalar l1 =
        ((px - a[0])*(c[1] - a[1]) - (c[0] - a[0])*(py - a[1]))/det;
    const scalar l2 =
        ((b[0] - a[0])*(py - a[1]) - (px - a[0])*(b[1] - a[1]))/det;
    const scalar l0 = 1 - l1 - l2;
    if (l0 >= -tolerance && l1 >= -tolerance && l2 >= -tolerance)
    {
        bary[0] = l0;
        bary[1] = l1;
        bary[2] = l2;
        return true;
    }
    return false;
}


Foam::label Foam::elementLocator::find
(
    const std::vector<scalar>& x,
    const std::vector<label>& elementNodes,
    const scalar px,
    const scalar py,
    scalar bary[3]
) const
{
    if (nx_ == 0) return -1;
    const scalar fi = (px - gx0_)*invCellSize_, fj = (py - gy0_)*invCellSize_;
    if (!(fi >= 0 && fj >= 0 && fi < nx_ && fj < ny_)) return -1;
    const label c = label(fj)*nx_ + label(fi);
    // Elements in increasing order: the first that contains the point is
    // the lowest-numbered one
    for (label k = cellStart_[c]; k < cellStart_[c + 1]; ++k)
    {
        const label el = cellElements_[k];
        if (contains(x, &elementNodes[3*el], px, py, bary)) return el;
    }
    return -1;
}


void Foam::elementLocator::overlapping
(
    const std::vector<scalar>& rectangles,
    std::vector<label>& out
) const
{
    if (nx_ == 0) return;
    // An element is listed in every cell its box overlaps: a bit per
    // element, then the set bits in increasing order (no sort)
    const std::size_t nWords = std::size_t(nElements_)/64 + 1;
    seen_.assign(nWords, 0);
    const auto cell = [](const scalar f, const label n)
    {
        return f <= 0 ? label(0) : f >= n - 1 ? n - 1 : label(f);
    };
    for (std::size_t r = 0; r + 3 < rectangles.size(); r += 4)
    {
        const scalar x0 = rectangles[r], y0 = rectangles[r + 1];
        const scalar x1 = rectangles[r + 2], y1 = rectangles[r + 3];
        // Empty, or beyond the grid: no element (each lies within its
        // enlarged box, inside the grid)
        if
        (
            !(x0 <= x1) || !(y0 <= y1)
         || x1 < gx0_ || y1 < gy0_
         || x0 > gx0_ + nx_*cellSize_ || y0 > gy0_ + ny_*cellSize_
        )
        {
            continue;
        }
        const label i0 = cell((x0 - gx0_)*invCellSize_, nx_);
        const label i1 = cell((x1 - gx0_)*invCellSize_, nx_);
        const label j0 = cell((y0 - gy0_)*invCellSize_, ny_);
        const label j1 = cell((y1 - gy0_)*invCellSize_, ny_);
        // A row's cells are consecutive in cellElements_
        for (label j = j0; j <= j1; ++j)
        {
            const label end = cellStart_[j*nx_ + i1 + 1];
            for (label k = cellStart_[j*nx_ + i0]; k < end; ++k)
            {
                const label el = cellElements_[k];
                seen_[el >> 6] |= std::uint64_t(1) << (el & 63);
            }
        }
    }
    for (std::size_t w = 0; w < nWords; ++w)
    {
        for (std::uint64_t bits = seen_[w]; bits; bits &= bits - 1)
        {
            out.push_back(label(64*w) + __builtin_ctzll(bits));
        }
    }
}


// ************************************************************************* //
