#include "triMesh.H"
#include "Time.H"
#include "vectorIOField.H"
#include "faceIOList.H"
#include "edgeIOList.H"
#include "labelIOList.H"
#include "wordIOList.H"

namespace
{

Foam::IOobject meshObject
(
    const Foam::Time& runTime,
    const Foam::word& name,
    const Foam::IOobject::readOption r
)
{
    return Foam::IOobject
    (
        name,
        runTime.constant(),
        Foam::triMesh::meshSubDir,
        runTime,
        r,
        Foam::IOobject::NO_WRITE,
        false
    );
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::triMesh Foam::triMesh::read(const Time& runTime)
{
    const IOobject::readOption r = IOobject::MUST_READ;

    const vectorIOField pts(meshObject(runTime, "points", r));
    const faceIOList tris(meshObject(runTime, "triangles", r));
    const labelIOList triRegion(meshObject(runTime, "triangleRegion", r));
    const wordIOList regionNames(meshObject(runTime, "regionNames", r));
    const edgeIOList segs(meshObject(runTime, "segments", r));
    const labelIOList segPatch(meshObject(runTime, "segmentPatch", r));
    const wordIOList patchNames(meshObject(runTime, "patchNames", r));

    std::vector<scalar> p(2*pts.size());
    forAll(pts, i)
    {
        p[2*i] = pts[i].x();
        p[2*i + 1] = pts[i].y();
    }
    std::vector<label> t(3*tris.size());
    forAll(tris, i)
    {
        if (tris[i].size() != 3)
        {
            FatalErrorInFunction
                << "Entry " << i << " of " << tris.objectPath()
                << " has " << tris[i].size() << " labels, not 3"
                << exit(FatalError);
        }
        for (label j = 0; j < 3; ++j) t[3*i + j] = tris[i][j];
    }
    std::vector<label> s(2*segs.size());
    forAll(segs, i)
    {
        s[2*i] = segs[i].first();
        s[2*i + 1] = segs[i].second();
    }

    return triMesh
    (
        std::move(p),
        std::move(t),
        std::vector<label>(triRegion.begin(), triRegion.end()),
        regionNames,
        std::move(s),
        std::vector<label>(segPatch.begin(), segPatch.end()),
        patchNames
    );
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::triMesh::write(const Time& runTime) const
{
    const IOobject::readOption r = IOobject::NO_READ;

    vectorIOField pts(meshObject(runTime, "points", r), nPoints());
    forAll(pts, i)
    {
        pts[i] = vector(points_[2*i], points_[2*i + 1], 0);
    }
    faceIOList tris(meshObject(runTime, "triangles", r), nTriangles());
    forAll(tris, i)
    {
        tris[i] = face(labelList({triangles_[3*i], triangles_[3*i + 1], triangles_[3*i + 2]}));
    }
    labelIOList triRegion(meshObject(runTime, "triangleRegion", r), nTriangles());
    forAll(triRegion, i) triRegion[i] = triangleRegion_[i];
    wordIOList regionNames(meshObject(runTime, "regionNames", r), regionNames_);
    edgeIOList segs(meshObject(runTime, "segments", r), nSegments());
    forAll(segs, i) segs[i] = edge(segments_[2*i], segments_[2*i + 1]);
    labelIOList segPatch(meshObject(runTime, "segmentPatch", r), nSegments());
    forAll(segPatch, i) segPatch[i] = segmentPatch_[i];
    wordIOList patchNames(meshObject(runTime, "patchNames", r), patchNames_);

    mkDir(runTime.path()/runTime.constant()/meshSubDir);
    const std::initializer_list<const regIOobject*> objects
    {
        &pts, &tris, &triRegion, &regionNames, &segs, &segPatch, &patchNames
    };
    for (const regIOobject* io : objects)
    {
        if (!io->regIOobject::write())
        {
            FatalErrorInFunction << "Cannot write " << io->objectPath()
                << exit(FatalError);
        }
    }
}


// ************************************************************************* //
