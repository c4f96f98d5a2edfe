#include "freeSurfaceProfile.H"
#include "checkKeywords.H"
#include "Time.H"
#include "OFstream.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(freeSurfaceProfile, 0);
    addToRunTimeSelectionTable(functionObject, freeSurfaceProfile, dictionary);
}
}


const Foam::Enum
<
    Foam::functionObjects::freeSurfaceProfile::particlePoint
>
Foam::functionObjects::freeSurfaceProfile::particlePointNames
({
    {particlePoint::centre, "centres"},
    {particlePoint::surface, "surface"}
});


namespace
{

//- The fluid particles binned on a square grid: which particle lies within
//  its own smoothing length of a point, on a given side of it
class particleBins
{
    Foam::scalar size_;
    std::unordered_map<long long, std::vector<Foam::label>> bins_;

    static long long key(const long long i, const long long j)
    {
        return (i << 32) ^ (j & 0xffffffffLL);
    }

    long long index(const Foam::scalar x) const
    {
        return static_cast<long long>(std::floor(x/size_));
    }

public:

    //- Bin the fluid particles of the model (cell size: the largest h)
    explicit particleBins(const Foam::spemModel& m)
    :
        size_(0)
    {
        if (!m.hasParticles()) return;
        const Foam::particleSet& ps = m.particles().particles();
        for (Foam::label i = 0; i < ps.size(); ++i)
        {
            if (ps.kinds()[i] != Foam::particleSet::kind::fluid) continue;
            size_ = std::max(size_, ps.smoothingLength()[i]);
        }
        if (!(size_ > 0)) return;
        for (Foam::label i = 0; i < ps.size(); ++i)
        {
            if (ps.kinds()[i] != Foam::particleSet::kind::fluid) continue;
            bins_[key
            (
                index(ps.positions()[2*i]), index(ps.positions()[2*i + 1])
            )].push_back(i);
        }
    }

    //- True if a fluid particle j lies within h_j of (x, y) and on the side
    //  of the unit normal (nx, ny): (x_j - x) . n > 0
    bool covers
    (
        const Foam::spemModel& m,
        const Foam::scalar x,
        const Foam::scalar y,
        const Foam::scalar nx,
        const Foam::scalar ny
    ) const
    {
        if (bins_.empty()) return false;
        const Foam::particleSet& ps = m.particles().particles();
        const long long ix = index(x), iy = index(y);
        for (long long i = ix - 1; i <= ix + 1; ++i)
        {
            for (long long j = iy - 1; j <= iy + 1; ++j)
            {
                const auto bin = bins_.find(key(i, j));
                if (bin == bins_.end()) continue;
                for (const Foam::label p : bin->second)
                {
                    const Foam::scalar rx = ps.positions()[2*p] - x;
                    const Foam::scalar ry = ps.positions()[2*p + 1] - y;
                    const Foam::scalar h = ps.smoothingLength()[p];
                    if (rx*rx + ry*ry < h*h && rx*nx + ry*ny > 0)
                    {
                        return true;
                    }
                }
            }
        }
        return false;
    }
};

} // End anonymous namespace


Foam::functionObjects::freeSurfaceProfile::freeSurfaceProfile
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    spemFunctionObject(name, runTime, dict),
    minDivR_(0.5),
    restrictX_(false),
    xMin_(-GREAT),
    xMax_(GREAT),
    topmostOnly_(false),
    binWidth_(0),
    particlePoints_(particlePoint::centre)
{
    read(dict);
    writeColumns({"points", "particles", "nodes"});
}


bool Foam::functionObjects::freeSurfaceProfile::read(const dictionary& dict)
{
    writeFile::read(dict);

    minDivR_ = dict.getOrDefault<scalar>("minDivR", 0.5);
    if (!(minDivR_ >= 0))
    {
        FatalIOErrorInFunction(dict)
            << "minDivR " << minDivR_ << " must be >= 0 (div r is 2 in the"
            << " bulk of the fluid)" << exit(FatalIOError);
    }

    restrictX_ = dict.found("xRange");
    xMin_ = -GREAT;
    xMax_ = GREAT;
    if (restrictX_)
    {
        const List<scalar> range = dict.get<List<scalar>>("xRange");
        if (range.size() != 2 || !(range[0] < range[1]))
        {
            FatalIOErrorInFunction(dict)
                << "xRange " << range << " must be two numbers (xMin xMax)"
                << " with xMin < xMax" << exit(FatalIOError);
        }
        xMin_ = range[0];
        xMax_ = range[1];
    }

    topmostOnly_ = dict.getOrDefault<Switch>("topmostOnly", false);
    particlePoints_ =
        getCheckedEnum
        (
            dict, "particlePoints", particlePointNames, particlePoint::centre
        );

    binWidth_ = 0;
    if (dict.found("binWidth"))
    {
        binWidth_ = dict.get<scalar>("binWidth");
        if (!(binWidth_ > 0))
        {
            FatalIOErrorInFunction(dict)
                << "binWidth " << binWidth_ << " must be > 0 (omit it for"
                << " the particle spacing)" << exit(FatalIOError);
        }
    }
    return true;
}


Foam::scalar
Foam::functionObjects::freeSurfaceProfile::particleSpacing() const
{
    const spemModel& m = model();
    const triMesh& mesh = m.mesh();
    if (m.hasElements())
    {
        const elementModel& em = m.elements();
        scalar area = 0;
        label n = 0;
        for (label t = 0; t < mesh.nTriangles(); ++t)
        {
            const label r = mesh.triangleRegion()[t];
            if (!em.hasMaterial(r) || !em.material(r).isFluid()) continue;
            area += mesh.triangleArea(t);
            ++n;
        }
        if (n > 0) return std::sqrt(area/n);
    }
    if (m.hasParticles())
    {
        const sphFluid& sph = m.particles();
        const particleSet& ps = sph.particles();
        scalar h = 0;
        label n = 0;
        for (label i = 0; i < ps.size(); ++i)
        {
            if (ps.kinds()[i] != particleSet::kind::fluid) continue;
            h += ps.smoothingLength()[i];
            ++n;
        }
        if (n > 0)
        {
            return h/n/sph.schemeControls().smoothingLengthRatio;
        }
    }
    return 0;
}


void Foam::functionObjects::freeSurfaceProfile::addParticles
(
    std::vector<std::pair<scalar, scalar>>& points
) const
{
    const spemModel& m = model();
    if (!m.hasParticles()) return;
    const sphFluid& sph = m.particles();
    const particleSet& ps = sph.particles();
    const scalar* x = ps.positions().data();
    const scalar* gradC = sph.gradC().data();
    // Half a spacing, h_i/smoothingLengthRatio/2, per unit h
    const scalar halfSpacing =
        particlePoints_ == particlePoint::surface
      ? 0.5/sph.schemeControls().smoothingLengthRatio
      : 0;
    for (label i = 0; i < ps.size(); ++i)
    {
        if (ps.kinds()[i] != particleSet::kind::fluid) continue;
        if (!sph.freeSurface(i) || sph.divR()[i] < minDivR_) continue;
        scalar px = x[2*i], py = x[2*i + 1];
        const scalar g = std::hypot(gradC[2*i], gradC[2*i + 1]);
        if (halfSpacing > 0 && g > 0)
        {
            // grad C points into the water: the surface lies the other way
            const scalar shift = halfSpacing*ps.smoothingLength()[i]/g;
            px -= shift*gradC[2*i];
            py -= shift*gradC[2*i + 1];
        }
        points.emplace_back(px, py);
    }
}


void Foam::functionObjects::freeSurfaceProfile::addElementNodes
(
    std::vector<std::pair<scalar, scalar>>& points
) const
{
    const spemModel& m = model();
    if (!m.hasElements()) return;
    const elementModel& em = m.elements();
    const triMesh& mesh = m.mesh();
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<label>& triRegion = mesh.triangleRegion();
    const std::vector<label>& triEdges = mesh.triangleEdges();
    const std::vector<label>& edgeTri = mesh.edgeTriangles();
    const std::vector<scalar>& x = em.positions();
    const List<patchType>& patchTypes = m.patchTypes();

    // Patch of each boundary edge (-1: none)
    std::vector<label> edgePatch(mesh.nEdges(), -1);
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        edgePatch[mesh.segmentEdge()[s]] = mesh.segmentPatch()[s];
    }

    const auto fluidRegion = [&](const label t)
    {
        const label r = triRegion[t];
        return em.hasMaterial(r) && em.material(r).isFluid();
    };

    const particleBins bins(m);
    std::vector<bool> taken(em.nNodes(), false);

    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        if (!fluidRegion(t) || em.removed(t)) continue;
        for (label i = 0; i < 3; ++i)
        {
            const label k = triEdges[3*t + i];
            const label other =
                edgeTri[2*k] == t ? edgeTri[2*k + 1] : edgeTri[2*k];

            // Side i joins nodes i and i+1 of the counter-clockwise
            // triangle: the element lies on its left
            const label a = tri[3*t + i];
            const label b = tri[3*t + (i + 1) % 3];

            bool free = false;
            bool mayBeCovered = false;
            if (other < 0)
            {
                // On a patch: free on a freeSurface patch, not on a wall
                free =
                    edgePatch[k] < 0
                 || patchTypes[edgePatch[k]] == patchType::freeSurface;
            }
            else if (!em.hasMaterial(triRegion[other]))
            {
                free = true;        // next to empty space (void region)
            }
            else if (em.removed(other))
            {
                free = true;        // next to a converted element ...
                mayBeCovered = true;    // ... unless particles fill it
            }
            if (!free) continue;

            const scalar ax = x[2*a], ay = x[2*a + 1];
            const scalar bx = x[2*b], by = x[2*b + 1];
            const scalar dx = bx - ax, dy = by - ay;
            const scalar l = std::hypot(dx, dy);
            if (!(l > 0)) continue;
            if
            (
                mayBeCovered
             && bins.covers(m, 0.5*(ax + bx), 0.5*(ay + by), dy/l, -dx/l)
            )
            {
                continue;
            }
            for (const label n : {a, b})
            {
                if (taken[n]) continue;
                taken[n] = true;
                points.emplace_back(x[2*n], x[2*n + 1]);
            }
        }
    }
}


bool Foam::functionObjects::freeSurfaceProfile::write()
{
    const spemModel& m = model();
    if (!m.hasElements()) particles();
    if (!writeToFile()) return true;

    std::vector<std::pair<scalar, scalar>> points;
    addParticles(points);
    const label nParticlePoints = label(points.size());
    addElementNodes(points);

    // Tag each point with its origin (particle first) through the order,
    // then filter and sort
    std::vector<std::pair<std::pair<scalar, scalar>, bool>> tagged;
    tagged.reserve(points.size());
    for (std::size_t p = 0; p < points.size(); ++p)
    {
        const scalar px = points[p].first;
        if (restrictX_ && (px < xMin_ || px > xMax_)) continue;
        tagged.push_back({points[p], label(p) < nParticlePoints});
    }

    if (topmostOnly_)
    {
        const scalar width = binWidth_ > 0 ? binWidth_ : particleSpacing();
        if (!(width > 0))
        {
            FatalErrorInFunction
                << "Function object " << name() << ": no particle spacing"
                << " for the bins (no fluid); set binWidth"
                << exit(FatalError);
        }
        const scalar origin = restrictX_ ? xMin_ : 0;
        std::unordered_map<long long, std::size_t> top;
        for (std::size_t p = 0; p < tagged.size(); ++p)
        {
            const long long bin = static_cast<long long>
            (
                std::floor((tagged[p].first.first - origin)/width)
            );
            const auto it = top.find(bin);
            if (it == top.end())
            {
                top.emplace(bin, p);
            }
            else if (tagged[p].first.second > tagged[it->second].first.second)
            {
                it->second = p;
            }
        }
        std::vector<std::pair<std::pair<scalar, scalar>, bool>> kept;
        kept.reserve(top.size());
        for (const auto& bin : top) kept.push_back(tagged[bin.second]);
        tagged.swap(kept);
    }

    std::sort
    (
        tagged.begin(), tagged.end(),
        [](const auto& p, const auto& q) { return p.first < q.first; }
    );

    label nParticles = 0;
    for (const auto& p : tagged) nParticles += p.second;

    // Next to the summary file, postProcessing/<name>/<startTime>/
    // (writeFile::baseTimeDir() names the current time, not the start)
    OFstream& summary = file();
    const fileName dir = summary.name().path()/time_.timeName();
    mkDir(dir);
    OFstream os(dir/(name() + ".dat"));
    os.precision(writePrecision_);
    os  << "# Free surface of " << name() << " at time "
        << time_.timeName() << ": " << tagged.size() << " points ("
        << nParticles << " particles, " << label(tagged.size()) - nParticles
        << " element nodes), sorted by x" << nl
        << "# x" << tab << "y" << nl;
    for (const auto& p : tagged)
    {
        os  << p.first.first << tab << p.first.second << nl;
    }

    summary
        << time_.value() << tab << tagged.size() << tab << nParticles << tab
        << label(tagged.size()) - nParticles << endl;
    return true;
}


// ************************************************************************* //
