/*---------------------------------------------------------------------------*\
Application
    spemMeshConvert

Description
    Converts a two-dimensional OpenFOAM mesh written by blockMesh
    (constant/polyMesh, one hexahedral cell thick in z, front and back
    patches of type empty) into the triangle mesh of the element half of
    SPEM (constant/spemMesh, see triMesh.H).

    - Nodes: the points of the front plane only (the empty face of each
      cell at the lower z), renumbered compactly in polyMesh point order.
    - Triangles: the front face (a quad) of each hex is split into two or
      four triangles according to the entry split (below).
    - Regions: one per cellZone, named after it; every cell must be in
      exactly one zone and every zone must have a material sub-dictionary
      regions/<zone> in constant/spemProperties.
    - Boundary segments: every face of a non-empty patch gives one segment
      (its two front-plane nodes) on a patch of the same name, in polyMesh
      patch order. Empty patches are dropped.

    Axisymmetric (wedge) meshes and meshes with symmetryPlane front/back
    patches are not supported, nor are non-hexahedral cells.

Usage
    spemMeshConvert [-case dir]

    Optional system/spemMeshConvertDict (defaults when the file or an entry
    is absent):

        // How each quad is split into triangles:
        //   alternating  two triangles, diagonal direction alternating
        //                between neighbouring cells (checkerboard /
        //                union-jack pattern, from a two-colouring of the
        //                cell adjacency graph)
        //   cross        four triangles around a new node at the quad's
        //                area centroid
        //   right        two triangles, every cell uses the "/" diagonal
        //   left         two triangles, every cell uses the "\" diagonal
        split   alternating;    // default: alternating

        // Optional: a different split for some regions (cellZones), e.g.
        // cross for thin elastic structures, whose bending locks with two
        // triangles per cell but not with four
        regionSplit
        {
            plate   cross;
        }

    The "/" diagonal of a quad is the one joining the two corners whose
    offset (dx, dy) has dx*dy > 0 (more precisely the diagonal with the
    larger dx*dy/|d|^2), "\" the other one. A diagonal that would make a
    non-convex quad's triangles overlap is replaced by the other one.

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "polyMesh.H"
#include "emptyPolyPatch.H"
#include "wedgePolyPatch.H"
#include "symmetryPlanePolyPatch.H"
#include "IOdictionary.H"
#include "Enum.H"
#include "triMesh.H"

#include <array>
#include <cmath>
#include <deque>
#include <vector>

using namespace Foam;

// * * * * * * * * * * * * * * * * * Helpers * * * * * * * * * * * * * * * * //

namespace
{

//- How the front quad of a cell is split into triangles
enum class splitType { alternating, cross, right, left };

const Enum<splitType> splitTypeNames
({
    { splitType::alternating, "alternating" },
    { splitType::cross, "cross" },
    { splitType::right, "right" },
    { splitType::left, "left" },
});

//- A unit normal component along z above this makes a face "normal to z"
//  (blockMesh writes planar front/back faces; the slack absorbs round-off)
const scalar zNormalTolerance = 1e-6;


//- Twice the signed area of the 2D triangle (a, b, c)
inline scalar twiceArea(const vector& a, const vector& b, const vector& c)
{
    return (b.x() - a.x())*(c.y() - a.y()) - (c.x() - a.x())*(b.y() - a.y());
}


//- How "/"-like the diagonal from a to b is: dx*dy/|d|^2 = sin(2 theta)/2,
//  positive for "/", negative for "\", independent of the cell size
inline scalar slashness(const vector& a, const vector& b)
{
    const scalar dx = b.x() - a.x(), dy = b.y() - a.y();
    return dx*dy/(dx*dx + dy*dy + VSMALL);
}


//- Whether the diagonal (q[i], q[i+2]) splits the quad q into two triangles
//  with the orientation of the quad (false for the reflex diagonal of a
//  non-convex quad)
bool diagonalIsValid(const std::array<vector, 4>& q, const label i)
{
    const scalar quadArea =
        twiceArea(q[0], q[1], q[2]) + twiceArea(q[0], q[2], q[3]);
    const vector& a = q[i];
    const vector& b = q[(i + 1)%4];
    const vector& c = q[(i + 2)%4];
    const vector& d = q[(i + 3)%4];
    return
        twiceArea(a, b, c)*quadArea > 0
     && twiceArea(a, c, d)*quadArea > 0;
}


//- Two-colour the cells through internal faces by breadth-first search.
//  Returns the colour (0 or 1) of each cell and the number of internal
//  faces whose two cells got the same colour (non-zero when the quad mesh
//  has interior vertices of odd valence, e.g. where three blocks meet)
labelList twoColourCells(const polyMesh& mesh, label& nConflicts)
{
    const labelList& own = mesh.faceOwner();
    const labelList& nei = mesh.faceNeighbour();
    const cellList& cells = mesh.cells();

    labelList colour(mesh.nCells(), -1);
    std::deque<label> front;
    for (label seed = 0; seed < mesh.nCells(); ++seed)
    {
        if (colour[seed] != -1) continue;
        colour[seed] = 0;
        front.push_back(seed);
        while (!front.empty())
        {
            const label celli = front.front();
            front.pop_front();
            for (const label facei : cells[celli])
            {
                if (!mesh.isInternalFace(facei)) continue;
                const label other =
                    (own[facei] == celli) ? nei[facei] : own[facei];
                if (colour[other] == -1)
                {
                    colour[other] = 1 - colour[celli];
                    front.push_back(other);
                }
            }
        }
    }

    nConflicts = 0;
    for (label facei = 0; facei < mesh.nInternalFaces(); ++facei)
    {
        if (colour[own[facei]] == colour[nei[facei]]) ++nConflicts;
    }
    return colour;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * * Main * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Convert a 2D blockMesh mesh (one cell thick in z, front/back patches"
        " of type empty, cellZones as material regions) into the SPEM"
        " triangle mesh constant/spemMesh.\n"
        "Options in the optional system/spemMeshConvertDict:"
        " split alternating|cross|right|left (default alternating)."
    );
    argList::noParallel();

    #include "setRootCase.H"
    #include "createTime.H"

    // Settings

    IOobject convertDictIO
    (
        "spemMeshConvertDict",
        runTime.system(),
        runTime,
        IOobject::READ_IF_PRESENT,
        IOobject::NO_WRITE
    );
    if (!convertDictIO.typeHeaderOk<IOdictionary>(true))
    {
        Info<< "No " << runTime.system()/convertDictIO.name()
            << ": using the default settings" << nl;
    }
    const IOdictionary convertDict(convertDictIO);

    // Read as a word first so that a bad value reports the keyword as well
    // as the file (Enum's own message names neither the keyword)
    auto readSplit = [](const dictionary& dict, const word& key)
    {
        const word splitName =
            dict.getOrDefault<word>(key, splitTypeNames[splitType::alternating]);
        if (!splitTypeNames.found(splitName))
        {
            FatalIOErrorInFunction(dict)
                << "Unknown value '" << splitName << "' of keyword '" << key
                << "' in " << dict.name() << nl
                << "Valid values of '" << key << "': "
                << splitTypeNames.sortedToc() << exit(FatalIOError);
        }
        return splitTypeNames[splitName];
    };
    const splitType split = readSplit(convertDict, "split");
    Info<< "Splitting quads: split " << splitTypeNames[split] << nl;
    const dictionary* regionSplitDict = convertDict.findDict("regionSplit");


    // Mesh

    Info<< "Reading polyMesh from "
        << runTime.constant()/polyMesh::meshSubDir << nl << endl;
    const polyMesh mesh
    (
        IOobject
        (
            polyMesh::defaultRegion,
            runTime.timeName(),
            runTime,
            IOobject::MUST_READ
        )
    );
    const polyBoundaryMesh& patches = mesh.boundaryMesh();
    const faceList& faces = mesh.faces();
    const cellList& cells = mesh.cells();
    const pointField& meshPoints = mesh.points();
    const vectorField& faceCentres = mesh.faceCentres();
    const vectorField& faceAreas = mesh.faceAreas();
    const vectorField& cellCentres = mesh.cellCentres();


    // Patches: empty ones are the 2D planes, the others become segments

    label nEmptyPatches = 0;
    for (const polyPatch& pp : patches)
    {
        if (isA<wedgePolyPatch>(pp))
        {
            FatalErrorInFunction
                << "Patch " << pp.name() << " is of type wedge: axisymmetric"
                << " meshes are not supported." << nl
                << "Use a planar 2D mesh one cell thick in z with the front"
                << " and back patches of type empty." << exit(FatalError);
        }
        if (isA<symmetryPlanePolyPatch>(pp))
        {
            // A symmetry line of the 2D domain is fine; a front/back one not
            bool normalToZ = false;
            forAll(pp, i)
            {
                const vector& a = faceAreas[pp.start() + i];
                if (mag(a.z()) > (1 - zNormalTolerance)*mag(a)) normalToZ = true;
            }
            if (normalToZ)
            {
                FatalErrorInFunction
                    << "Patch " << pp.name() << " of type symmetryPlane is"
                    << " normal to z: symmetryPlane front/back patches are"
                    << " not supported." << nl
                    << "Make the front and back patches of type empty."
                    << exit(FatalError);
            }
        }
        if (isA<emptyPolyPatch>(pp)) ++nEmptyPatches;
    }
    if (nEmptyPatches == 0)
    {
        FatalErrorInFunction
            << "Mesh is not 2D: no patch is of type empty." << nl
            << "spemMeshConvert needs a blockMesh mesh one cell thick in z"
            << " whose front and back patches are of type empty"
            << " (e.g. frontAndBack { type empty; faces (...); })."
            << exit(FatalError);
    }

    auto onEmptyPatch = [&](const label facei)
    {
        const label patchi = patches.whichPatch(facei);
        return patchi >= 0 && isA<emptyPolyPatch>(patches[patchi]);
    };


    // Cells: hexes with exactly two faces (front, back) on empty patches

    labelList frontFace(mesh.nCells(), -1);
    {
        label nNotHex = 0, firstNotHex = -1;
        label nNot2D = 0, firstNot2D = -1;
        label nNotZ = 0, firstNotZ = -1;

        forAll(cells, celli)
        {
            const cell& c = cells[celli];
            label emptyFaces[2] = {-1, -1};
            label nEmpty = 0;
            for (const label facei : c)
            {
                if (onEmptyPatch(facei))
                {
                    if (nEmpty < 2) emptyFaces[nEmpty] = facei;
                    ++nEmpty;
                }
            }
            if (nEmpty != 2)
            {
                if (!nNot2D++) firstNot2D = celli;
                continue;
            }
            // The front face is the one at the lower z
            const label f0 = emptyFaces[0], f1 = emptyFaces[1];
            const bool firstIsFront = faceCentres[f0].z() < faceCentres[f1].z();
            const label front = firstIsFront ? f0 : f1;
            const label back = firstIsFront ? f1 : f0;
            const vector n = faceAreas[front]/(mag(faceAreas[front]) + VSMALL);
            if
            (
                mag(n.z()) < 1 - zNormalTolerance
             || faceCentres[back].z() <= faceCentres[front].z()
            )
            {
                if (!nNotZ++) firstNotZ = celli;
                continue;
            }
            if (c.size() != 6 || faces[front].size() != 4)
            {
                if (!nNotHex++) firstNotHex = celli;
                continue;
            }
            frontFace[celli] = front;
        }

        if (nNot2D)
        {
            FatalErrorInFunction
                << "Mesh is not 2D: " << nNot2D << " of " << mesh.nCells()
                << " cells do not have exactly two faces on empty patches,"
                << " e.g. the cell at " << cellCentres[firstNot2D] << nl
                << "spemMeshConvert needs a mesh one cell thick in z (blocks"
                << " with 1 cell in z) whose front and back patches are of"
                << " type empty." << exit(FatalError);
        }
        if (nNotZ)
        {
            FatalErrorInFunction
                << "Mesh is not 2D in the x-y plane: the empty faces of "
                << nNotZ << " cells are not front/back faces normal to z,"
                << " e.g. the cell at " << cellCentres[firstNotZ] << nl
                << "Build the mesh in the x-y plane, one cell thick in z."
                << exit(FatalError);
        }
        if (nNotHex)
        {
            FatalErrorInFunction
                << nNotHex << " cells are not hexahedra (6 faces, a front face"
                << " with 4 points), e.g. the cell at "
                << cellCentres[firstNotHex] << " with "
                << cells[firstNotHex].size() << " faces" << nl
                << "Collapsed (prism) blocks are not supported."
                << exit(FatalError);
        }
    }


    // Regions from cellZones

    const cellZoneMesh& zones = mesh.cellZones();
    if (zones.empty())
    {
        FatalErrorInFunction
            << "The mesh has no cellZones: every cell needs a zone, which"
            << " names its material region." << nl
            << "Name the zone of each block in system/blockMeshDict, e.g."
            << nl << "    hex (0 1 2 3 4 5 6 7) water (20 40 1)"
            << " simpleGrading (1 1 1)" << nl
            << "and give each zone a material in constant/spemProperties"
            << " regions { water { ... } }." << exit(FatalError);
    }
    const wordList regionNames(zones.names());

    labelList cellRegion(mesh.nCells(), -1);
    forAll(zones, zonei)
    {
        for (const label celli : zones[zonei])
        {
            if (cellRegion[celli] != -1 && cellRegion[celli] != zonei)
            {
                FatalErrorInFunction
                    << "The cell at " << cellCentres[celli] << " is in"
                    << " cellZones " << regionNames[cellRegion[celli]]
                    << " and " << regionNames[zonei] << nl
                    << "Each cell must be in exactly one zone."
                    << exit(FatalError);
            }
            cellRegion[celli] = zonei;
        }
    }
    {
        label nNoZone = 0, firstNoZone = -1;
        forAll(cellRegion, celli)
        {
            if (cellRegion[celli] == -1 && !nNoZone++) firstNoZone = celli;
        }
        if (nNoZone)
        {
            FatalErrorInFunction
                << nNoZone << " of " << mesh.nCells() << " cells are in no"
                << " cellZone, e.g. the cell at "
                << cellCentres[firstNoZone] << nl
                << "Name the zone of every block in system/blockMeshDict,"
                << " e.g. hex (0 1 2 3 4 5 6 7) water (20 40 1)"
                << " simpleGrading (1 1 1)" << exit(FatalError);
        }
    }


    // Every region needs a material

    {
        const IOdictionary properties
        (
            IOobject
            (
                "spemProperties",
                runTime.constant(),
                runTime,
                IOobject::MUST_READ,
                IOobject::NO_WRITE
            )
        );
        const dictionary& regionsDict = properties.subDict("regions");
        for (const word& zoneName : regionNames)
        {
            if (!regionsDict.isDict(zoneName))
            {
                FatalIOErrorInFunction(regionsDict)
                    << "cellZone " << zoneName << " has no material: keyword"
                    << " regions/" << zoneName << " (a sub-dictionary) is"
                    << " missing in " << properties.objectPath() << nl
                    << "Materials found: " << regionsDict.toc() << nl
                    << "Add e.g. regions { " << zoneName
                    << " { model ...; rho ...; } }" << exit(FatalIOError);
            }
        }
    }


    // Split of each cell: the default, or its region's regionSplit entry
    List<splitType> cellSplit(mesh.nCells(), split);
    if (regionSplitDict)
    {
        for (const entry& e : *regionSplitDict)
        {
            const label r = regionNames.find(e.keyword());
            if (r < 0)
            {
                FatalIOErrorInFunction(*regionSplitDict)
                    << "regionSplit names " << e.keyword() << ", which is not"
                    << " a cellZone. cellZones: " << regionNames
                    << exit(FatalIOError);
            }
            const splitType zoneSplit = readSplit(*regionSplitDict, e.keyword());
            Info<< "    region " << e.keyword() << ": split "
                << splitTypeNames[zoneSplit] << nl;
            forAll(cellSplit, celli)
            {
                if (cellRegion[celli] == r) cellSplit[celli] = zoneSplit;
            }
        }
    }
    Info<< endl;

    // Centre node of each cross-split cell, numbered after the front nodes
    labelList centreNodeOfCell(mesh.nCells(), -1);
    label nCentreNodes = 0;
    bool anyAlternating = false;
    forAll(cellSplit, celli)
    {
        if (cellSplit[celli] == splitType::cross)
        {
            centreNodeOfCell[celli] = nCentreNodes++;
        }
        anyAlternating = anyAlternating || cellSplit[celli] == splitType::alternating;
    }


    // Nodes: front-plane points, compact labels in polyMesh point order

    labelList nodeOfPoint(mesh.nPoints(), -1);
    forAll(frontFace, celli)
    {
        for (const label pointi : faces[frontFace[celli]])
        {
            nodeOfPoint[pointi] = 0;
        }
    }
    label nFrontNodes = 0;
    for (label& n : nodeOfPoint)
    {
        if (n == 0) n = nFrontNodes++;
    }

    const label nNodes = nFrontNodes + nCentreNodes;
    std::vector<scalar> nodes(2*nNodes);
    forAll(nodeOfPoint, pointi)
    {
        const label n = nodeOfPoint[pointi];
        if (n >= 0)
        {
            nodes[2*n] = meshPoints[pointi].x();
            nodes[2*n + 1] = meshPoints[pointi].y();
        }
    }


    // Triangles

    label nColourConflicts = 0;
    labelList colour =
        anyAlternating
      ? twoColourCells(mesh, nColourConflicts)
      : labelList(mesh.nCells(), 0);
    forAll(cellSplit, celli)
    {
        if (cellSplit[celli] == splitType::right) colour[celli] = 0;
        if (cellSplit[celli] == splitType::left) colour[celli] = 1;
    }

    std::vector<label> triangles;
    std::vector<label> triangleRegion;
    triangles.reserve(3*(2*mesh.nCells() + 2*nCentreNodes));
    triangleRegion.reserve(2*mesh.nCells() + 2*nCentreNodes);
    label nDiagonalsSwapped = 0;

    forAll(frontFace, celli)
    {
        const face& f = faces[frontFace[celli]];
        const std::array<label, 4> node
        {
            nodeOfPoint[f[0]], nodeOfPoint[f[1]],
            nodeOfPoint[f[2]], nodeOfPoint[f[3]]
        };
        const std::array<vector, 4> q
        {
            meshPoints[f[0]], meshPoints[f[1]],
            meshPoints[f[2]], meshPoints[f[3]]
        };

        if (cellSplit[celli] == splitType::cross)
        {
            // Area centroid of the quad from its two triangles (0 1 2), (0 2 3)
            const scalar a012 = twiceArea(q[0], q[1], q[2]);
            const scalar a023 = twiceArea(q[0], q[2], q[3]);
            const vector centroid =
                (a012*(q[0] + q[1] + q[2]) + a023*(q[0] + q[2] + q[3]))
               /(3*(a012 + a023));
            const label centreNode = nFrontNodes + centreNodeOfCell[celli];
            nodes[2*centreNode] = centroid.x();
            nodes[2*centreNode + 1] = centroid.y();
            for (label i = 0; i < 4; ++i)
            {
                if
                (
                    twiceArea(q[i], q[(i + 1)%4], centroid)*(a012 + a023)
                 <= 0
                )
                {
                    FatalErrorInFunction
                        << "The cell at " << cellCentres[celli] << " is too"
                        << " distorted for split cross: its centroid is not"
                        << " inside it. Use split alternating."
                        << exit(FatalError);
                }
                triangles.insert
                (
                    triangles.end(), {node[i], node[(i + 1)%4], centreNode}
                );
                triangleRegion.push_back(cellRegion[celli]);
            }
            continue;
        }

        // Two triangles: diagonal (q[d], q[d+2]) with d = 0 or 1; colour 0
        // takes the "/" diagonal, colour 1 the "\" one
        const bool zeroTwoIsSlash =
            slashness(q[0], q[2]) >= slashness(q[1], q[3]);
        label d = ((colour[celli] == 0) == zeroTwoIsSlash) ? 0 : 1;
        if (!diagonalIsValid(q, d))
        {
            d = 1 - d;
            ++nDiagonalsSwapped;
            if (!diagonalIsValid(q, d))
            {
                FatalErrorInFunction
                    << "The front face of the cell at " << cellCentres[celli]
                    << " is degenerate (no diagonal splits it into two"
                    << " positive triangles)" << exit(FatalError);
            }
        }
        triangles.insert
        (
            triangles.end(),
            {
                node[d], node[(d + 1)%4], node[(d + 2)%4],
                node[d], node[(d + 2)%4], node[(d + 3)%4]
            }
        );
        triangleRegion.push_back(cellRegion[celli]);
        triangleRegion.push_back(cellRegion[celli]);
    }


    // Boundary segments from the non-empty patches

    wordList patchNames;
    std::vector<label> segments;
    std::vector<label> segmentPatch;
    List<scalar> patchLength;
    for (const polyPatch& pp : patches)
    {
        if (isA<emptyPolyPatch>(pp)) continue;
        const label patchi = patchNames.size();
        patchNames.append(pp.name());
        patchLength.append(0);
        forAll(pp, i)
        {
            const face& f = pp[i];
            label ends[2] = {-1, -1};
            label nFront = 0;
            for (const label pointi : f)
            {
                if (nodeOfPoint[pointi] >= 0)
                {
                    if (nFront < 2) ends[nFront] = nodeOfPoint[pointi];
                    ++nFront;
                }
            }
            if (f.size() != 4 || nFront != 2)
            {
                FatalErrorInFunction
                    << "Face " << i << " of patch " << pp.name() << " at "
                    << faceCentres[pp.start() + i] << " has " << f.size()
                    << " points, " << nFront << " of them on the front plane"
                    << " (expected 4 and 2)" << exit(FatalError);
            }
            segments.push_back(ends[0]);
            segments.push_back(ends[1]);
            segmentPatch.push_back(patchi);
            patchLength[patchi] += std::hypot
            (
                nodes[2*ends[1]] - nodes[2*ends[0]],
                nodes[2*ends[1] + 1] - nodes[2*ends[0] + 1]
            );
        }
    }


    // Build (orients and checks) and write

    const triMesh spemMesh
    (
        std::move(nodes),
        std::move(triangles),
        std::move(triangleRegion),
        regionNames,
        std::move(segments),
        std::move(segmentPatch),
        patchNames
    );

    Info<< "polyMesh" << nl
        << "    cells:     " << mesh.nCells() << nl
        << "    points:    " << mesh.nPoints() << nl << nl
        << "spemMesh" << nl
        << "    nodes:     " << spemMesh.nPoints() << nl
        << "    triangles: " << spemMesh.nTriangles() << nl
        << "    edges:     " << spemMesh.nEdges() << nl
        << "    segments:  " << spemMesh.nSegments() << nl;
    if (anyAlternating && nColourConflicts)
    {
        Info<< "    note: " << nColourConflicts << " pairs of neighbouring"
            << " cells share a diagonal direction (odd cycles in the cell"
            << " graph, e.g. where three blocks meet)" << nl;
    }
    if (nDiagonalsSwapped)
    {
        Info<< "    note: " << nDiagonalsSwapped << " non-convex cells use"
            << " the other diagonal" << nl;
    }

    Info<< nl << "Patches (segments, length)" << nl;
    {
        labelList nSegs(spemMesh.nPatches(), 0);
        for (const label p : spemMesh.segmentPatch()) ++nSegs[p];
        forAll(patchNames, patchi)
        {
            Info<< "    " << patchNames[patchi] << ": " << nSegs[patchi]
                << " segments, length " << patchLength[patchi] << nl;
        }
    }

    Info<< nl << "Regions (triangles, area)" << nl;
    {
        labelList nTris(spemMesh.nRegions(), 0);
        for (const label r : spemMesh.triangleRegion()) ++nTris[r];
        forAll(regionNames, regioni)
        {
            Info<< "    " << regionNames[regioni] << ": " << nTris[regioni]
                << " triangles, area " << spemMesh.regionArea(regioni) << nl;
        }
        Info<< "    total area: " << spemMesh.regionArea() << nl << endl;
    }

    Info<< "Writing " << runTime.constant()/triMesh::meshSubDir << nl;
    spemMesh.write(runTime);

    Info<< nl << "End" << nl << endl;

    return 0;
}


// ************************************************************************* //
