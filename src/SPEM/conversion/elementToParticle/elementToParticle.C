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
    particleSet& particles,
    const scalar refinedRadiusRatio,
    refinementChange* change
)
{
    const label first = particles.size();
    const bool refine = refinedRadiusRatio > 0;
    particles.reserve(first + (refine ? 3 : 1)*label(elements.size()));

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

        if (!refine)
        {
            // Eq. (18): the particle carries the element's mass and density
            particles.append
            (
                xM, yM, uM, vM, m/area, 0, m,
                smoothingLengthRatio*std::sqrt(area)
            );
            continue;
        }

        // Eqs. (19-22): three particles halfway between M and the nodes,
        // each a third of the mass at the element's density, with the
        // velocity of its node; radius refinedRadiusRatio R_M, R_M =
        // sqrt(A_e)/2, hence spacing refinedRadiusRatio sqrt(A_e)
        const scalar hRefined =
            smoothingLengthRatio*refinedRadiusRatio*std::sqrt(area);
        scalar dL = 0, dE = 0;
        for (label k = 0; k < 3; ++k)
        {
            const scalar* xn = &x[2*n[k]];
            const scalar* vn = &v[2*n[k]];
            const scalar xi = 0.5*(xn[0] + xM), yi = 0.5*(xn[1] + yM);
            particles.append
            (
                xi, yi, vn[0], vn[1], m/area, 0, m/3, hRefined,
                particleSet::kind::fluid, 1
            );
            // About x_M, where M's own angular momentum is zero
            dL += m/3*((xi - xM)*vn[1] - (yi - yM)*vn[0]);
            dE += m/6*(sqr(vn[0] - uM) + sqr(vn[1] - vM));
        }
        if (change)
        {
            change->angularMomentum += dL;
            change->kineticEnergy += dE;
            change->unsplitKineticEnergy += 0.5*m*(uM*uM + vM*vM);
        }
    }
    return first;
}


void Foam::convertElements
(
    const triMesh& mesh,
    const std::vector<label>& triangles,
    const scalar smoothingLengthRatio,
    elementModel& elements,
    particleSet& particles,
    const scalar refinedRadiusRatio,
    refinementChange* change
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
        triangles, smoothingLengthRatio, particles, refinedRadiusRatio,
        change
    );
    elements.removeTriangles(mesh, triangles);
}


// ************************************************************************* //
