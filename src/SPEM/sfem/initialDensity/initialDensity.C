#include "initialDensity.H"
#include "weaklyCompressibleNewtonian.H"
#include "error.H"

#include <cmath>
#include <limits>

namespace
{

using namespace Foam;

//- The free surface of region r: the highest node (height against
//  gravity g) of the edges the region shares with a freeSurface patch or a
//  void region; -max() if none
scalar freeSurfaceHeight
(
    const triMesh& mesh,
    const List<patchType>& patchTypes,
    const PtrList<spemMaterial>& materials,
    const label r,
    const scalar gx,
    const scalar gy
)
{
    const std::vector<scalar>& x = mesh.points();
    const std::vector<label>& triRegion = mesh.triangleRegion();

    // Patch of each edge, -1 for interior edges
    std::vector<label> edgePatch(mesh.nEdges(), -1);
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        edgePatch[mesh.segmentEdge()[s]] = mesh.segmentPatch()[s];
    }
    const scalar g = std::sqrt(gx*gx + gy*gy);

    scalar eta = -std::numeric_limits<scalar>::max();
    for (label e = 0; e < mesh.nEdges(); ++e)
    {
        const label t0 = mesh.edgeTriangles()[2*e];
        const label t1 = mesh.edgeTriangles()[2*e + 1];
        const bool in0 = triRegion[t0] == r;
        const bool in1 = t1 >= 0 && triRegion[t1] == r;
        if (in0 == in1) continue;
        const label other = in0 ? t1 : t0;
        const bool free =
            other < 0
          ? (
                edgePatch[e] >= 0
             && patchTypes[edgePatch[e]] == patchType::freeSurface
            )
          : !materials.set(triRegion[other]);
        if (!free) continue;
        for (label k = 0; k < 2; ++k)
        {
            const label n = mesh.edges()[2*e + k];
            eta = std::max(eta, -(gx*x[2*n] + gy*x[2*n + 1])/g);
        }
    }
    return eta;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * Function  * * * * * * * * * * * * * * * //

std::vector<Foam::scalar> Foam::initialDensity
(
    const triMesh& mesh,
    const List<patchType>& patchTypes,
    const PtrList<spemMaterial>& materials,
    const dictionary& regionsDict,
    const scalar gx,
    const scalar gy
)
{
    const std::vector<scalar>& x = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<label>& triRegion = mesh.triangleRegion();
    const label nTri = mesh.nTriangles();

    std::vector<scalar> rho(nTri, 0);
    for (label t = 0; t < nTri; ++t)
    {
        const label r = triRegion[t];
        if (materials.set(r)) rho[t] = materials[r].rho();
    }

    const scalar g = std::sqrt(gx*gx + gy*gy);
    // Height against gravity
    const auto height = [&](const scalar px, const scalar py)
    {
        return -(gx*px + gy*py)/g;
    };

    forAll(materials, r)
    {
        if (!materials.set(r) || !materials[r].isFluid()) continue;
        const auto* fluid =
            dynamic_cast<const weaklyCompressibleNewtonian*>(&materials[r]);
        if (!fluid || !fluid->hydrostaticStart()) continue;

        const word& name = mesh.regionNames()[r];
        const dictionary& dict = regionsDict.subDict(name);
        if (!(g > 0))
        {
            FatalIOErrorInFunction(dict)
                << "initialPressure hydrostatic of region " << name
                << " needs gravity (constant/g)" << exit(FatalIOError);
        }

        const scalar eta =
            freeSurfaceHeight(mesh, patchTypes, materials, r, gx, gy);
        if (eta == -std::numeric_limits<scalar>::max())
        {
            FatalIOErrorInFunction(dict)
                << "initialPressure hydrostatic of region " << name
                << " needs a free surface: the region has no edge on a"
                << " freeSurface patch or next to a void region"
                << exit(FatalIOError);
        }

        // rho0 exp(g d/c^2): dp/dz = -rho g with p = c^2 (rho - rho0)
        const scalar rho0 = fluid->rho(), c2 = fluid->c()*fluid->c();
        scalar rhoMax = rho0;
        for (label t = 0; t < nTri; ++t)
        {
            if (triRegion[t] != r) continue;
            const label* n = &tri[3*t];
            const scalar cx = (x[2*n[0]] + x[2*n[1]] + x[2*n[2]])/3;
            const scalar cy = (x[2*n[0] + 1] + x[2*n[1] + 1] + x[2*n[2] + 1])/3;
            const scalar depth = std::max(eta - height(cx, cy), scalar(0));
            rho[t] = rho0*std::exp(g*depth/c2);
            rhoMax = std::max(rhoMax, rho[t]);
        }
        Info<< "Region " << name << ": hydrostatic initial pressure below the"
            << " free surface at height " << eta << " m, at most "
            << c2*(rhoMax - rho0) << " Pa" << nl;
    }
    return rho;
}


// ************************************************************************* //
