#include "SPH.H"
#include "initialDensity.H"
#include "elementToParticle.H"
#include "weaklyCompressibleNewtonian.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace spemMethods
{
    defineTypeNameAndDebug(SPH, 0);
    addToRunTimeSelectionTable(spemMethod, SPH, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

const Foam::weaklyCompressibleNewtonian&
Foam::spemMethods::SPH::fluidTriangles
(
    const PtrList<spemMaterial>& materials,
    std::vector<label>& fluidElements
) const
{
    const triMesh& mesh = case_.mesh;

    // The fluid regions: one fluid for the particles
    const weaklyCompressibleNewtonian* fluid = nullptr;
    forAll(materials, r)
    {
        if (!materials.set(r)) continue;
        const spemMaterial& mat = materials[r];
        const auto* f = dynamic_cast<const weaklyCompressibleNewtonian*>(&mat);
        if (!f)
        {
            FatalIOErrorInFunction(case_.properties)
                << "Region " << mesh.regionNames()[r] << " (" << mat.type()
                << "): method SPH couples particles to solid regions, which"
                << " this version cannot do yet. Use method SPEM for"
                << " structures, or make the region a fluid or void"
                << exit(FatalIOError);
        }
        if (!sameFluid(fluid, *f))
        {
            FatalIOErrorInFunction(case_.properties)
                << "Fluid regions with different rho, c or mu: the particle"
                << " half models one fluid" << exit(FatalIOError);
        }
        fluid = f;
        for (label t = 0; t < mesh.nTriangles(); ++t)
        {
            if (mesh.triangleRegion()[t] == r) fluidElements.push_back(t);
        }
    }
    // The water a body displaces at t = 0 is not there
    const std::vector<label> inside = trianglesInsideBodies();
    if (!inside.empty())
    {
        std::sort(fluidElements.begin(), fluidElements.end());
        std::vector<label> kept;
        std::set_difference
        (
            fluidElements.begin(), fluidElements.end(),
            inside.begin(), inside.end(), std::back_inserter(kept)
        );
        fluidElements.swap(kept);
    }
    if (!fluid)
    {
        FatalIOErrorInFunction(case_.properties)
            << "method SPH needs at least one fluid region"
            << exit(FatalIOError);
    }
    return *fluid;
}


void Foam::spemMethods::SPH::buildParticles
(
    const PtrList<spemMaterial>& materials,
    const std::vector<scalar>& density
)
{
    const triMesh& mesh = case_.mesh;
    std::vector<label> fluidElements;
    const weaklyCompressibleNewtonian& fluid =
        fluidTriangles(materials, fluidElements);

    // Eqs. (17-18): every fluid element becomes a particle at t = 0
    std::vector<scalar> elementMass(mesh.nTriangles(), 0);
    scalar areaSum = 0;
    for (const label t : fluidElements)
    {
        const scalar area = mesh.triangleArea(t);
        elementMass[t] = density[t]*area;
        areaSum += area;
    }
    const sphFluid::controls ctrl = sphFluid::controls::read(case_.schemes);
    particleSet ps;
    std::vector<scalar> rhoOld;
    const bool restart = case_.restart.readParticles(ps, rhoOld);
    if (!restart && case_.restart.restarting())
    {
        FatalErrorInFunction
            << "The restart state " << case_.restart.startPath()
            << " has no particlePositions: method SPH needs the fluid"
            << " particles (a state written by another method?)"
            << exit(FatalError);
    }
    if (restart && ps.size() != label(fluidElements.size()))
    {
        FatalErrorInFunction
            << "The restart state of time " << case_.runTime.timeName()
            << " has " << ps.size() << " fluid particles; the mesh has "
            << fluidElements.size() << " fluid elements, each one"
            << " particle with method SPH. Is the state from another"
            << " mesh? (Allclean removes it.)" << exit(FatalError);
    }
    if (!restart)
    {
        const std::vector<scalar> v(mesh.points().size(), 0);
        appendParticlesFromElements
        (
            mesh.points(), v, mesh.triangles(), elementMass, fluidElements,
            ctrl.smoothingLengthRatio, ps
        );
    }
    const label nFluid = ps.size();
    createParticleHalf
    (
        std::move(ps), std::move(rhoOld), fluid,
        std::sqrt(areaSum/fluidElements.size())
    );
    Info<< "Particles (method SPH): " << nFluid << " fluid particles from "
        << fluidElements.size() << " fluid elements" << nl;

    // Initial relaxation of the barycentres (sphFluid.H), once, at t = 0;
    // a restart reads the relaxed positions
    if (!restart) relaxInitialParticles();
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemMethods::SPH::SPH
(
    const spemCase& c,
    PtrList<spemMaterial>& materials
)
:
    spemMethod(c)
{
    // The bulk viscosity is a stress of the fluid elements, which become
    // particles here. Not an error: a tutorial that sets it for SPEM keeps
    // the entry when a user switches it to SPH
    forAll(materials, r)
    {
        if (materials.set(r) && materials[r].bulkViscosity() > 0)
        {
            IOWarningInFunction(c.properties)
                << "regions/" << materials[r].name() << "/bulkViscosity "
                << materials[r].bulkViscosity() << " damps the fluid"
                << " elements only; method SPH has none and ignores it"
                << endl;
        }
    }
    const std::vector<scalar> density =
        initialDensity
        (
            c.mesh, c.patchTypes, materials, c.properties.subDict("regions"),
            c.g[0], c.g[1]
        );
    if (!anySolid(materials))
    {
        buildParticles(materials, density);
        return;
    }

    // Solids are elements: the fluid elements become particles at t = 0
    // and couple to them (eq. 27)
    createElementHalf(materials, density);
    const std::vector<label> inside = trianglesInsideBodies();
    if (!inside.empty())
    {
        elements_->removeTriangles(c.mesh, inside);
        Info<< "    rigid bodies: " << inside.size() << " fluid elements"
            << " inside them removed" << nl;
    }
    scalar maxArea;
    const std::vector<bool> fluid = surveyFluidElements(maxArea);
    if (!elementFluid_ || restartConversions()) return;

    std::vector<label> all;
    for (label t = 0; t < c.mesh.nTriangles(); ++t)
    {
        if (fluid[t] && !elements_->removed(t)) all.push_back(t);
    }
    if (!all.empty())
    {
        convert(all);
        Info<< "    " << all.size()
            << " fluid elements became particles at t = 0" << nl;
        // Once, at t = 0 (sphFluid.H); a restart reads the relaxed state
        relaxInitialParticles();
    }
}


// ************************************************************************* //
