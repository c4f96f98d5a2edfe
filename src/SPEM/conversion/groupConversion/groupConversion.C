#include "groupConversion.H"
#include "elementModel.H"
#include "checkKeywords.H"
#include "parallelLoop.H"
#include "simdLanes.H"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <cmath>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::groupConversion::groupConversion
(
    const dictionary& conversionDict,
    const triMesh& mesh,
    const std::vector<bool>& fluidTriangle,
    const scalar hMax,
    const bodySurfaces& bodies
)
:
    criterion_(distortionCriterion::New(conversionDict)),
    presetRegions_(readPresetParticleRegions(conversionDict, mesh, bodies)),
    groupSizeFactor_
    (
        conversionDict.getOrDefault<scalar>("groupSizeFactor", 1.5)
    ),
    groupSize_(groupSizeFactor_*2*hMax),
    bodyReach_(conversionDict.getOrDefault<scalar>("bodyReach", 1)),
    triangleGroup_(mesh.nTriangles(), -1)
{
    checkKeywords
    (
        conversionDict,
        {
            "criterion", "minInteriorAngle", "maxStretchRatio",
            "groupSizeFactor", "bodyReach", "presetParticleRegions",
            "refinedRadiusRatio"    // multiResolutionSPEM's
        }
    );
    if (!(groupSizeFactor_ > 1 && groupSizeFactor_ <= 10))
    {
        FatalIOErrorInFunction(conversionDict)
            << "conversion/groupSizeFactor (lambda) must lie in (1, 10],"
            << " found " << groupSizeFactor_ << exit(FatalIOError);
    }
    if (!(bodyReach_ >= 1 && bodyReach_ <= 10))
    {
        FatalIOErrorInFunction(conversionDict)
            << "conversion/bodyReach (particle supports round the bodies"
            << " whose fluid elements convert) must lie in [1, 10], found "
            << bodyReach_ << exit(FatalIOError);
    }
    if (!(hMax > 0))
    {
        FatalErrorInFunction
            << "Largest smoothing length " << hMax << " must be positive"
            << exit(FatalError);
    }

    listGroupTriangles(assignGroups(mesh, fluidTriangle));
    findNeighbours(mesh);

    const std::vector<scalar>& X = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    referenceEdges_.resize(4*mesh.nTriangles());
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        distortionCriterion::referenceEdges
        (
            &X[2*tri[3*t]], &X[2*tri[3*t + 1]], &X[2*tri[3*t + 2]],
            &referenceEdges_[4*t]
        );
    }
}


Foam::label Foam::groupConversion::assignGroups
(
    const triMesh& mesh,
    const std::vector<bool>& fluidTriangle
)
{
    // The grid over the fluid elements' reference centroids
    const std::vector<scalar>& X = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    const label nTri = mesh.nTriangles();
    std::vector<scalar> centroid(2*nTri, 0);
    scalar lo[2] = {GREAT, GREAT}, hi[2] = {-GREAT, -GREAT};
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluidTriangle[t]) continue;
        for (int k = 0; k < 2; ++k)
        {
            centroid[2*t + k] =
                (X[2*tri[3*t] + k] + X[2*tri[3*t + 1] + k] + X[2*tri[3*t + 2] + k])
               /3;
            lo[k] = std::min(lo[k], centroid[2*t + k]);
            hi[k] = std::max(hi[k], centroid[2*t + k]);
        }
    }
    label nx = 0, ny = 0;
    if (lo[0] <= hi[0])
    {
        nx = label(std::floor((hi[0] - lo[0])/groupSize_)) + 1;
        ny = label(std::floor((hi[1] - lo[1])/groupSize_)) + 1;
    }

    // Squares without elements get no group: number the occupied ones
    std::vector<label> square(nTri, -1);
    std::vector<label> squareGroup(nx*ny, -1);
    label nGroups = 0;
    for (label t = 0; t < nTri; ++t)
    {
        if (!fluidTriangle[t]) continue;
        const label ix = std::min
        (
            label((centroid[2*t] - lo[0])/groupSize_), nx - 1
        );
        const label iy = std::min
        (
            label((centroid[2*t + 1] - lo[1])/groupSize_), ny - 1
        );
        square[t] = iy*nx + ix;
        if (squareGroup[square[t]] < 0) squareGroup[square[t]] = nGroups++;
        triangleGroup_[t] = squareGroup[square[t]];
    }
    return nGroups;
}


void Foam::groupConversion::listGroupTriangles(const label nGroups)
{
    const label nTri = triangleGroup_.size();
    groupStart_.assign(nGroups + 1, 0);
    for (label t = 0; t < nTri; ++t)
    {
        if (triangleGroup_[t] >= 0) ++groupStart_[triangleGroup_[t] + 1];
    }
    for (label g = 0; g < nGroups; ++g) groupStart_[g + 1] += groupStart_[g];
    groupTriangles_.resize(groupStart_[nGroups]);
    {
        std::vector<label> fill(groupStart_.begin(), groupStart_.end() - 1);
        for (label t = 0; t < nTri; ++t)
        {
            if (triangleGroup_[t] >= 0)
            {
                groupTriangles_[fill[triangleGroup_[t]]++] = t;
            }
        }
    }
}


void Foam::groupConversion::findNeighbours(const triMesh& mesh)
{
    const label nTri = mesh.nTriangles();
    triangleNeighbours_.assign(3*nTri, -1);
    for (label t = 0; t < nTri; ++t)
    {
        for (label i = 0; i < 3; ++i)
        {
            const label k = mesh.triangleEdges()[3*t + i];
            const label t0 = mesh.edgeTriangles()[2*k];
            const label t1 = mesh.edgeTriangles()[2*k + 1];
            triangleNeighbours_[3*t + i] = t0 == t ? t1 : t0;
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

std::vector<Foam::label>
Foam::groupConversion::presetTriangles(const triMesh& mesh) const
{
    std::vector<label> out;
    if (presetRegions_.empty()) return out;

    const std::vector<scalar>& X = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        if (triangleGroup_[t] < 0) continue;
        const label* n = &tri[3*t];
        const scalar cx = (X[2*n[0]] + X[2*n[1]] + X[2*n[2]])/3;
        const scalar cy = (X[2*n[0] + 1] + X[2*n[1] + 1] + X[2*n[2] + 1])/3;
        for (const presetParticleRegion& r : presetRegions_)
        {
            if (r.contains(cx, cy))
            {
                out.push_back(t);
                break;
            }
        }
    }
    return out;
}


std::vector<Foam::label>
Foam::groupConversion::trianglesToConvert
(
    const elementModel& elements,
    const std::vector<label>& forcedTriangles
)
{
    // criterion none: no run-time conversion, no cost
    const bool none = criterion_->type() == "none";
    if (none && forcedTriangles.empty()) return std::vector<label>();
    if (none)
    {
        distorted_.clear();
    }
    else
    {
        markDistorted(elements);
    }
    const std::vector<label>& triangle = elements.elementTriangle();

    // Scratch kept between steps: no allocation in the time loop
    std::vector<bool>& convert = convertGroup_;
    convert.assign(nGroups(), false);
    bool any = false;
    for (const label el : distorted_)
    {
        const label g = triangleGroup_[triangle[el]];
        if (g < 0) continue;
        convert[g] = true;
        any = true;
    }
    for (const label t : forcedTriangles)
    {
        const label g = triangleGroup_[t];
        if (g < 0 || elements.removed(t)) continue;
        convert[g] = true;
        any = true;
    }

    std::vector<label> out;
    if (!any) return out;
    std::vector<bool> converting(triangleGroup_.size(), false);
    for (label g = 0; g < nGroups(); ++g)
    {
        if (!convert[g]) continue;
        for (label k = groupStart_[g]; k < groupStart_[g + 1]; ++k)
        {
            const label t = groupTriangles_[k];
            if (!elements.removed(t))
            {
                out.push_back(t);
                converting[t] = true;
            }
        }
    }
    addRemnants(elements, out, converting);
    std::sort(out.begin(), out.end());
    return out;
}


void Foam::groupConversion::markDistorted(const elementModel& elements)
{
    const std::vector<scalar>& x = elements.positions();
    const std::vector<label>& nodes = elements.elementNodes();
    const std::vector<label>& triangle = elements.elementTriangle();
    const distortionCriterion& criterion = *criterion_;
    const label nNodes = elements.nNodes();
    if (4*elements.nMeshTriangles() != label(referenceEdges_.size()))
    {
        FatalErrorInFunction
            << "The element model is not of the conversion's mesh ("
            << elements.nMeshTriangles() << " against "
            << referenceEdges_.size()/4 << " triangles)" << exit(FatalError);
    }
    distorted_.clear();
    ++nCalls_;

    // The fluid elements: ranges of the regions
    const auto fluidRegion = [&](const label r)
    {
        return elements.hasMaterial(r) && elements.material(r).isFluid();
    };

    // The nodes that have moved beyond their slack since the whole pass
    bool whole =
        passBuild_ != elements.buildStamp()
     || label(passX_.size()) != 2*nNodes;
    if (!whole)
    {
        // A flag per node, a node's (x, y) as one pair, then the flags
        // read eight at a time: most are clear
        movedNodes_.clear();
        movedFlags_.resize(nNodes + 8);
        unsigned char* moved = movedFlags_.data();
        const scalar* xp = passX_.data();
        const scalar* slack = nodeSlack_.data();
        const scalar* xn = x.data();
        for (label n = 0; n < nNodes; ++n)
        {
            // Not "|d| >= slack": a NaN position counts as moved
            simd::pair now, then;
            std::memcpy(&now, xn + 2*n, sizeof now);
            std::memcpy(&then, xp + 2*n, sizeof then);
            const simd::pair d = now - then;
            const simd::pair s = {slack[n], slack[n]};
            const auto within = (d < s) & (d > -s);
            moved[n] = !(within[0] & within[1]);
        }
        std::fill(moved + nNodes, moved + nNodes + 8, 0);
        for (label n = 0; n < nNodes; n += 8)
        {
            std::uint64_t word;
            std::memcpy(&word, moved + n, 8);
            if (!word) continue;
            for (label k = n; k < n + 8; ++k)
            {
                if (moved[k]) movedNodes_.push_back(k);
            }
        }
        whole = 10*label(movedNodes_.size()) > nNodes;
    }

    if (whole)
    {
        ++nWholePasses_;
        const label nEl = elements.nElements();
        flags_.resize(nEl);
        elementSlack_.resize(nEl);
        passX_ = x;
        nodeSlack_.assign(nNodes, VGREAT);
        passBuild_ = elements.buildStamp();
        for (label r = 0; r < elements.regions().size(); ++r)
        {
            if (!fluidRegion(r)) continue;
            const label begin = elements.regions()[r].elemBegin;
            const label end = elements.regions()[r].elemEnd;
            criterion.markDistortedWithSlack
            (
                begin, end, nodes.data(), x.data(), triangle.data(),
                referenceEdges_.data(), flags_.data(), elementSlack_.data()
            );
            for (label el = begin; el < end; ++el)
            {
                if (flags_[el]) distorted_.push_back(el);
                const scalar s = elementSlack_[el];
                for (label k = 0; k < 3; ++k)
                {
                    scalar& ns = nodeSlack_[nodes[3*el + k]];
                    ns = s > 0 ? std::min(ns, s) : 0;
                }
            }
        }
        return;
    }

    // The fluid elements of the moved nodes, each once: the same test
    // (nodeElements() holds 3 el + the node's corner)
    const std::vector<label>& start = elements.nodeElementStart();
    const std::vector<label>& slots = elements.nodeElements();
    listedAt_.resize(elements.nElements(), 0);
    candidates_.clear();
    for (const label n : movedNodes_)
    {
        for (label i = start[n]; i < start[n + 1]; ++i)
        {
            const label el = slots[i]/3;
            if (listedAt_[el] == nCalls_) continue;
            listedAt_[el] = nCalls_;
            for (label r = 0; r < elements.regions().size(); ++r)
            {
                if
                (
                    el >= elements.regions()[r].elemBegin
                 && el < elements.regions()[r].elemEnd
                )
                {
                    if (fluidRegion(r)) candidates_.push_back(el);
                    break;
                }
            }
        }
    }
    const label nCandidates = label(candidates_.size());
    nElementsTested_ += nCandidates;
    flags_.resize(max(label(flags_.size()), nCandidates));
    criterion.markDistortedOf
    (
        candidates_.data(), nCandidates, nodes.data(), x.data(),
        triangle.data(), referenceEdges_.data(), flags_.data()
    );
    for (label i = 0; i < nCandidates; ++i)
    {
        if (flags_[i]) distorted_.push_back(candidates_[i]);
    }
}


void Foam::groupConversion::addRemnants
(
    const elementModel& elements,
    std::vector<label>& out,
    std::vector<bool>& converting
) const
{
    // Remnants: fluid elements left with at most one fluid element
    // neighbour, peeled until none is left (a queue over the neighbours of
    // what converts)
    const auto remains = [&](const label t)
    {
        return
            t >= 0 && triangleGroup_[t] >= 0 && !elements.removed(t)
         && !converting[t];
    };
    std::vector<label> queue(out);
    while (!queue.empty())
    {
        const label t = queue.back();
        queue.pop_back();
        for (label i = 0; i < 3; ++i)
        {
            const label u = triangleNeighbours_[3*t + i];
            if (!remains(u)) continue;
            label nNeighbours = 0;
            for (label j = 0; j < 3; ++j)
            {
                if (remains(triangleNeighbours_[3*u + j])) ++nNeighbours;
            }
            if (nNeighbours <= 1)
            {
                converting[u] = true;
                out.push_back(u);
                queue.push_back(u);
            }
        }
    }
}


void Foam::groupConversion::describe(Ostream& os) const
{
    os  << "Conversion: ";
    criterion_->describe(os);
    os  << ", groups of " << groupSize_ << " m (groupSizeFactor "
        << groupSizeFactor_ << "), " << nGroups() << " groups";
    if (bodyReach_ != 1)
    {
        os  << ", particles " << bodyReach_ << " supports round the bodies";
    }
    if (presetRegions_.size())
    {
        os  << ", " << presetRegions_.size() << " preset particle regions";
    }
    os  << nl;
}


// ************************************************************************* //
