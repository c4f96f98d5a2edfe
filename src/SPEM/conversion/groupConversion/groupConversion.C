#include "groupConversion.H"
#include "elementModel.H"
#include "checkKeywords.H"
#include "parallelLoop.H"

#include <algorithm>
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
        distorted_.assign(elements.nElements(), 0);
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
    for (label el = 0; el < elements.nElements(); ++el)
    {
        if (!distorted_[el]) continue;
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
    const distortionCriterion& criterion = *criterion_;
    distorted_.assign(elements.nElements(), 0);
    if (4*elements.nMeshTriangles() != label(referenceEdges_.size()))
    {
        FatalErrorInFunction
            << "The element model is not of the conversion's mesh ("
            << elements.nMeshTriangles() << " against "
            << referenceEdges_.size()/4 << " triangles)" << exit(FatalError);
    }

    for (label r = 0; r < elements.regions().size(); ++r)
    {
        if (!elements.hasMaterial(r) || !elements.material(r).isFluid())
        {
            continue;
        }
        const label begin = elements.regions()[r].elemBegin;
        const label end = elements.regions()[r].elemEnd;

        // Performance critical: every fluid element, every step
        criterion.markDistorted
        (
            begin, end, nodes.data(), x.data(),
            elements.elementTriangle().data(), referenceEdges_.data(),
            distorted_.data()
        );
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
