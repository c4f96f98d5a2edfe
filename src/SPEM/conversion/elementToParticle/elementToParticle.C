#include "elementToParticle.H"
#include "elementModel.H"
#include "error.H"

#include <cmath>

// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

Foam::label Foam::appendParticlesFromElements
(
    const std::vector<scalar>& x,
    const std::vector<scalar>& v,
    const std::vector<label>& triangleNodes,
    const std::vector<scalar>& elementMass,
    const std::vector<label>& elements,
    const scalar smoothingLengthRatio,
    particleSet& particles
)
{
    const label first = particles.size();
    particles.reserve(first + label(elements.size()));

    for (const label e : elements)
    {
        const label* n = &triangleNodes[3*e];
        const scalar* a = &x[2*n[0]];
        const scalar* b = &x[2*n[1]];
        const scalar* c = &x[2*n[2]];
        const scalar area =
            0.5*std::abs((b[0] - a[0])*(c[1] - a[1]) - (b[1] - a[1])*(c[0] - a[0]));
        const scalar m = elementMass[e];
        if (!(area > 0) || !(m > 0))
        {
            FatalErrorInFunction
                << "Element " << e << " has area " << area << " and mass " << m
                << ": cannot become a particle" << exit(FatalError);
        }

        // Eq. (17) with the equal nodal shares m_e/3 of a linear triangle
        const scalar xM = (a[0] + b[0] + c[0])/3;
        const scalar yM = (a[1] + b[1] + c[1])/3;
        const scalar uM = (v[2*n[0]] + v[2*n[1]] + v[2*n[2]])/3;
        const scalar vM = (v[2*n[0] + 1] + v[2*n[1] + 1] + v[2*n[2] + 1])/3;

        // Eq. (18): the particle carries the element's mass and density
        particles.append
        (
            xM, yM, uM, vM, m/area, 0, m, smoothingLengthRatio*std::sqrt(area)
        );
    }
    return first;
}


void Foam::convertElements
(
    const triMesh& mesh,
    const std::vector<label>& triangles,
    const scalar smoothingLengthRatio,
    elementModel& elements,
    particleSet& particles
)
{
    std::vector<scalar> mass(mesh.nTriangles(), 0);
    for (label el = 0; el < elements.nElements(); ++el)
    {
        mass[elements.elementTriangle()[el]] = elements.elementMass()[el];
    }
    for (const label t : triangles)
    {
        if (t < 0 || t >= mesh.nTriangles() || elements.removed(t))
        {
            FatalErrorInFunction
                << "Triangle " << t << " is not an element of the model"
                << exit(FatalError);
        }
    }
    appendParticlesFromElements
    (
        elements.positions(), elements.velocities(), mesh.triangles(), mass,
        triangles, smoothingLengthRatio, particles
    );
    elements.removeTriangles(mesh, triangles);
}


// ************************************************************************* //
