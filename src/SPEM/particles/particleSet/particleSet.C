#include "particleSet.H"
#include "parallelLoop.H"
#include "error.H"

#include <algorithm>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using Foam::label;

//- Loops shorter than this run on one thread (core/parallelLoop)
using Foam::minParallelLoop;

template<class Type>
std::size_t capacityBytes(const std::vector<Type>& v)
{
    return v.capacity()*sizeof(Type);
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

template<class Type>
void Foam::particleSet::permute
(
    const std::vector<label>& newToOld,
    const label nComp,
    std::vector<Type>& field,
    std::vector<Type>& scratch
)
{
    const label n = label(newToOld.size());
    scratch.resize(nComp*n);

    // Performance critical when reordering every step: a gather, streaming
    // writes and (for particles already nearly sorted) nearly streaming reads
    const label* __restrict__ order = newToOld.data();
    const Type* __restrict__ from = field.data();
    Type* __restrict__ to = scratch.data();
    if (nComp == 1)
    {
        #pragma omp parallel for schedule(static) if(n > minParallelLoop)
        for (label i = 0; i < n; ++i)
        {
            to[i] = from[order[i]];
        }
    }
    else
    {
        #pragma omp parallel for schedule(static) if(n > minParallelLoop)
        for (label i = 0; i < n; ++i)
        {
            for (label c = 0; c < nComp; ++c)
            {
                to[nComp*i + c] = from[nComp*order[i] + c];
            }
        }
    }
    field.swap(scratch);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::particleSet::particleSet(const label n)
{
    resize(n);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::particleSet::resize(const label n)
{
    const label old = size();
    position_.resize(2*n, 0);
    velocity_.resize(2*n, 0);
    density_.resize(n, 0);
    pressure_.resize(n, 0);
    mass_.resize(n, 0);
    h_.resize(n, 0);
    kind_.resize(n, kind::fluid);
    level_.resize(n, 0);
    id_.resize(n);
    for (label i = old; i < n; ++i)
    {
        id_[i] = i;
    }
}


void Foam::particleSet::reserve(const label n)
{
    position_.reserve(2*n);
    velocity_.reserve(2*n);
    density_.reserve(n);
    pressure_.reserve(n);
    mass_.reserve(n);
    h_.reserve(n);
    kind_.reserve(n);
    level_.reserve(n);
    id_.reserve(n);
}


Foam::label Foam::particleSet::append
(
    const scalar x,
    const scalar y,
    const scalar u,
    const scalar v,
    const scalar rho,
    const scalar p,
    const scalar m,
    const scalar h,
    const kind k,
    const unsigned char lev
)
{
    const label i = size();
    position_.push_back(x);
    position_.push_back(y);
    velocity_.push_back(u);
    velocity_.push_back(v);
    density_.push_back(rho);
    pressure_.push_back(p);
    mass_.push_back(m);
    h_.push_back(h);
    kind_.push_back(k);
    level_.push_back(lev);
    id_.push_back(i);
    return i;
}


void Foam::particleSet::reorder(const std::vector<label>& newToOld)
{
    const label n = size();
    if (label(newToOld.size()) != n)
    {
        FatalErrorInFunction
            << "Reorder of " << n << " particles given an order of "
            << newToOld.size() << " particles" << exit(FatalError);
    }

    #ifdef FULLDEBUG
    {
        std::vector<bool> seen(n, false);
        for (const label o : newToOld)
        {
            if (o < 0 || o >= n || seen[o])
            {
                FatalErrorInFunction
                    << "The order is not a permutation: " << o
                    << " out of range or repeated" << exit(FatalError);
            }
            seen[o] = true;
        }
    }
    #endif

    permute(newToOld, 2, position_, vectorScratch_);
    permute(newToOld, 2, velocity_, vectorScratch_);
    permute(newToOld, 1, density_, scalarScratch_);
    permute(newToOld, 1, pressure_, scalarScratch_);
    permute(newToOld, 1, mass_, scalarScratch_);
    permute(newToOld, 1, h_, scalarScratch_);
    permute(newToOld, 1, kind_, kindScratch_);
    permute(newToOld, 1, level_, levelScratch_);
    permute(newToOld, 1, id_, labelScratch_);
}


void Foam::particleSet::reorderField
(
    const std::vector<label>& newToOld,
    const label nComp,
    std::vector<scalar>& field
)
{
    const label n = label(newToOld.size());
    if (n != size() || label(field.size()) != nComp*n)
    {
        FatalErrorInFunction
            << "Reorder of a field of " << field.size() << " values ("
            << nComp << " per particle) given an order of " << n
            << " particles; the set has " << size() << exit(FatalError);
    }
    permute
    (
        newToOld, nComp, field, nComp == 2 ? vectorScratch_ : scalarScratch_
    );
}


Foam::scalar Foam::particleSet::maxSmoothingLength() const
{
    const label n = size();
    const scalar* __restrict__ h = h_.data();
    scalar hMax = 0;
    #pragma omp parallel for schedule(static) reduction(max: hMax) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        hMax = std::max(hMax, h[i]);
    }
    return hMax;
}


std::size_t Foam::particleSet::memoryBytes() const
{
    return
        capacityBytes(position_) + capacityBytes(velocity_)
      + capacityBytes(density_) + capacityBytes(pressure_)
      + capacityBytes(mass_) + capacityBytes(h_)
      + capacityBytes(kind_) + capacityBytes(level_) + capacityBytes(id_)
      + capacityBytes(vectorScratch_) + capacityBytes(scalarScratch_)
      + capacityBytes(kindScratch_) + capacityBytes(levelScratch_)
      + capacityBytes(labelScratch_);
}


Foam::scalar Foam::particleSet::memoryBytesPerParticle() const
{
    return size() > 0 ? scalar(memoryBytes())/size() : 0;
}


// ************************************************************************* //
