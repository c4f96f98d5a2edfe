#include "patchDistanceRegion.H"
#include "checkKeywords.H"
#include "triMesh.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>

namespace Foam
{
    defineTypeNameAndDebug(patchDistanceRegion, 0);
    addToRunTimeSelectionTable
    (
        presetParticleRegion,
        patchDistanceRegion,
        dictionary
    );
}


Foam::patchDistanceRegion::patchDistanceRegion
(
    const word& name,
    const dictionary& dict,
    const triMesh& mesh,
    const bodySurfaces& bodies
)
:
    presetParticleRegion(name)
{
    checkKeywords(dict, {"type", "patches", "bodies", "distance"});

    if (!dict.found("patches") && !dict.found("bodies"))
    {
        FatalIOErrorInFunction(dict)
            << dict.name() << " needs 'patches' (mesh patches: "
            << mesh.patchNames() << ") or 'bodies' (rigid bodies of"
            << " constant/rigidBodyProperties), or both" << exit(FatalIOError);
    }

    const wordList patches(dict.getOrDefault<wordList>("patches", wordList()));
    if (dict.found("patches") && patches.empty())
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'patches' of " << dict.name() << " is empty. Mesh"
            << " patches: " << mesh.patchNames() << exit(FatalIOError);
    }

    std::vector<bool> selected(mesh.nPatches(), false);
    for (const word& patch : patches)
    {
        const label patchi = mesh.findPatch(patch);
        if (patchi < 0)
        {
            FatalIOErrorInFunction(dict)
                << "Unknown patch " << patch << " in entry 'patches' of "
                << dict.name() << ". Mesh patches: " << mesh.patchNames()
                << exit(FatalIOError);
        }
        selected[patchi] = true;
    }

    for (const word& body : dict.getOrDefault<wordList>("bodies", wordList()))
    {
        const auto b = std::find_if
        (
            bodies.begin(),
            bodies.end(),
            [&](const bodySurface& s) { return s.name == body; }
        );
        if (b == bodies.end())
        {
            wordList names(label(bodies.size()));
            forAll(names, i) names[i] = bodies[i].name;
            FatalIOErrorInFunction(dict)
                << "Unknown rigid body " << body << " in entry 'bodies' of "
                << dict.name() << ". Bodies of constant/rigidBodyProperties: "
                << names << exit(FatalIOError);
        }
        bodies_.push_back(*b);
    }

    distance_ = readPositive(dict, "distance");

    const std::vector<scalar>& points = mesh.points();
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        if (!selected[mesh.segmentPatch()[s]]) continue;
        const label a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
        segments_.insert
        (
            segments_.end(),
            {points[2*a], points[2*a + 1], points[2*b], points[2*b + 1]}
        );
    }
}


bool Foam::patchDistanceRegion::contains(const scalar x, const scalar y) const
{
    for (const bodySurface& body : bodies_)
    {
        if (body.signedDistance(x, y) <= distance_) return true;
    }

    const scalar distance2 = distance_*distance_;
    const label n = nSegments();
    for (label s = 0; s < n; ++s)
    {
        const scalar* seg = segments_.data() + 4*s;
        const scalar ex = seg[2] - seg[0], ey = seg[3] - seg[1];
        const scalar px = x - seg[0], py = y - seg[1];

        // Parameter of the closest point of the segment, clamped to it
        const scalar length2 = ex*ex + ey*ey;
        const scalar t =
            length2 > 0
          ? std::min(std::max((px*ex + py*ey)/length2, scalar(0)), scalar(1))
          : scalar(0);
        const scalar dx = px - t*ex, dy = py - t*ey;
        if (dx*dx + dy*dy <= distance2)
        {
            return true;
        }
    }
    return false;
}
