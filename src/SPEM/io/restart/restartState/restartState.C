#include "restartState.H"
#include "elementModel.H"
#include "sphFluid.H"
#include "wallAcceleration.H"
#include "rigidBodies.H"
#include "bodyElementCoupling.H"
#include "vectorIOField.H"
#include "scalarIOField.H"
#include "labelIOList.H"
#include "IOdictionary.H"
#include "OFstream.H"
#include "OSspecific.H"

#include <algorithm>

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::IOobject Foam::restartState::file
(
    const word& name,
    const IOobject::readOption r
) const
{
    return IOobject
    (
        name, runTime_.timeName(), "spem", runTime_, r, IOobject::NO_WRITE,
        false
    );
}


void Foam::restartState::writeParticles(const sphFluid& particles) const
{
    const particleSet& ps = particles.particles();
    const label nFluid = particles.nFluid();
    const IOobject xIO(file("particlePositions", IOobject::NO_READ));
    vectorIOField xf(xIO, nFluid);
    vectorIOField vf(IOobject(xIO, "particleU"), nFluid);
    scalarIOField rho(IOobject(xIO, "particleRho"), nFluid);
    scalarIOField rhoOld(IOobject(xIO, "particleRhoOld"), nFluid);
    scalarIOField m(IOobject(xIO, "particleMass"), nFluid);
    scalarIOField h(IOobject(xIO, "particleH"), nFluid);

    // In the order of the particle ids, so that a restart reproduces the
    // same particle set
    std::vector<label> order;
    for (label i = 0; i < ps.size(); ++i)
    {
        if (ps.kinds()[i] == particleSet::kind::fluid) order.push_back(i);
    }
    std::sort
    (
        order.begin(), order.end(),
        [&](const label a, const label b) { return ps.id()[a] < ps.id()[b]; }
    );
    forAll(xf, k)
    {
        const label i = order[k];
        xf[k] = vector(ps.positions()[2*i], ps.positions()[2*i + 1], 0);
        vf[k] = vector(ps.velocities()[2*i], ps.velocities()[2*i + 1], 0);
        rho[k] = ps.density()[i];
        rhoOld[k] = particles.oldDensity()[i];
        m[k] = ps.mass()[i];
        h[k] = ps.smoothingLength()[i];
    }
    xf.write();
    vf.write();
    rho.write();
    rhoOld.write();
    m.write();
    h.write();
}


void Foam::restartState::writeAcceleration
(
    const word& name,
    const wallAcceleration& wa
) const
{
    const IOobject uIO(file(name + "OldU", IOobject::NO_READ));
    vectorIOField U(uIO, wa.size());
    vectorIOField A(IOobject(uIO, name + "Acceleration"), wa.size());
    forAll(U, k)
    {
        U[k] = vector(wa.oldVelocities()[2*k], wa.oldVelocities()[2*k + 1], 0);
        A[k] = vector(wa.accelerations()[2*k], wa.accelerations()[2*k + 1], 0);
    }
    U.write();
    A.write();
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::restartState::restartState(const Time& runTime)
:
    runTime_(runTime)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::restartState::write(const content& c) const
{
    mkDir(runTime_.timePath()/"spem");
    if (c.particles) writeParticles(*c.particles);
    if (c.virtualParticles)
    {
        writeAcceleration("virtualParticle", *c.virtualParticles);
    }
    if (c.bodyParticles) writeAcceleration("bodyParticle", *c.bodyParticles);
    if (c.bodies && !c.bodies->empty())
    {
        IOdictionary state(file("rigidBodies", IOobject::NO_READ));
        c.bodies->writeState(state);
        // All digits: the restart continues the same motion exactly
        OFstream os(state.objectPath());
        os.precision(17);
        state.writeHeader(os);
        state.writeData(os);
    }
    if (c.bodyNodes)
    {
        const bodyElementCoupling& be = *c.bodyNodes;
        labelIOList pairs(file("bodyNodes", IOobject::NO_READ), 2*be.size());
        for (label k = 0; k < be.size(); ++k)
        {
            pairs[2*k] = be.nodes()[k];
            pairs[2*k + 1] = be.bodies()[k];
        }
        pairs.write();
    }
    if (c.convertedTriangles && !c.convertedTriangles->empty())
    {
        const std::vector<label>& t = *c.convertedTriangles;
        labelIOList converted
        (
            file("convertedTriangles", IOobject::NO_READ), label(t.size())
        );
        forAll(converted, i) converted[i] = t[i];
        converted.write();
    }
    if (c.elements)
    {
        const std::vector<scalar>& x = c.elements->positions();
        const std::vector<scalar>& v = c.elements->velocities();
        const label n = c.elements->nNodes();
        const IOobject xIO(file("points", IOobject::NO_READ));
        vectorIOField xf(xIO, n);
        vectorIOField vf(IOobject(xIO, "U"), n);
        for (label i = 0; i < n; ++i)
        {
            xf[i] = vector(x[2*i], x[2*i + 1], 0);
            vf[i] = vector(v[2*i], v[2*i + 1], 0);
        }
        xf.write();
        vf.write();
    }
}


bool Foam::restartState::readElements(elementModel& elements) const
{
    IOobject xIO(file("points", IOobject::MUST_READ));
    if (!xIO.typeHeaderOk<vectorIOField>(true)) return false;

    const vectorIOField xf(xIO);
    const vectorIOField vf(IOobject(xIO, "U"));
    const label nNodes = elements.nNodes();
    if (xf.size() != nNodes || vf.size() != nNodes)
    {
        FatalErrorInFunction
            << "Restart state in " << xIO.path() << " has " << xf.size()
            << " points and " << vf.size() << " velocities; the mesh has "
            << nNodes << " nodes" << exit(FatalError);
    }
    std::vector<scalar> x(2*xf.size()), v(2*vf.size());
    forAll(xf, i)
    {
        x[2*i] = xf[i].x();
        x[2*i + 1] = xf[i].y();
        v[2*i] = vf[i].x();
        v[2*i + 1] = vf[i].y();
    }
    elements.setState(x, v);
    Info<< "Restart: read node positions and velocities from "
        << xIO.path() << nl << endl;
    return true;
}


bool Foam::restartState::readParticles
(
    particleSet& particles,
    std::vector<scalar>& rhoOld
) const
{
    IOobject xIO(file("particlePositions", IOobject::MUST_READ));
    if (!xIO.typeHeaderOk<vectorIOField>(true)) return false;

    const vectorIOField xf(xIO);
    const vectorIOField vf(IOobject(xIO, "particleU"));
    const scalarIOField rho(IOobject(xIO, "particleRho"));
    const scalarIOField m(IOobject(xIO, "particleMass"));
    const scalarIOField h(IOobject(xIO, "particleH"));
    const label n = xf.size();
    if (vf.size() != n || rho.size() != n || m.size() != n || h.size() != n)
    {
        FatalErrorInFunction
            << "Restart particle state in " << xIO.path() << " is"
            << " inconsistent: " << n << " positions, " << vf.size()
            << " velocities, " << rho.size() << " densities, " << m.size()
            << " masses, " << h.size() << " smoothing lengths"
            << exit(FatalError);
    }
    particles.reserve(n);
    forAll(xf, i)
    {
        particles.append
        (
            xf[i].x(), xf[i].y(), vf[i].x(), vf[i].y(), rho[i], 0, m[i], h[i]
        );
    }

    // Densities at the start of the step (volumes of the next evaluation);
    // a state without them restarts with the current ones
    IOobject oldIO(xIO, "particleRhoOld");
    rhoOld.assign(rho.begin(), rho.end());
    if (oldIO.typeHeaderOk<scalarIOField>(true))
    {
        const scalarIOField old(oldIO);
        if (old.size() == n) rhoOld.assign(old.begin(), old.end());
    }
    Info<< "Restart: read " << n << " fluid particles from " << xIO.path()
        << nl << endl;
    return true;
}


void Foam::restartState::readAcceleration
(
    const word& name,
    wallAcceleration& wa
) const
{
    IOobject uIO(file(name + "OldU", IOobject::MUST_READ));
    if (!uIO.typeHeaderOk<vectorIOField>(true)) return;
    const vectorIOField U(uIO);
    const vectorIOField A(IOobject(uIO, name + "Acceleration"));
    if (U.size() != wa.size() || A.size() != wa.size())
    {
        FatalErrorInFunction
            << "The restart state " << uIO.objectPath() << " has "
            << U.size() << " moving wall particles; the case has "
            << wa.size() << ". Is the state from another mesh or"
            << " body set-up? (Allclean removes it.)"
            << exit(FatalError);
    }
    std::vector<scalar> u(2*U.size()), a(2*A.size());
    forAll(U, k)
    {
        u[2*k] = U[k].x();
        u[2*k + 1] = U[k].y();
        a[2*k] = A[k].x();
        a[2*k + 1] = A[k].y();
    }
    wa.restart(u, a);
}


bool Foam::restartState::readConvertedTriangles
(
    std::vector<label>& triangles
) const
{
    IOobject cIO(file("convertedTriangles", IOobject::MUST_READ));
    if (!cIO.typeHeaderOk<labelIOList>(true)) return false;
    const labelIOList converted(cIO);
    triangles.assign(converted.begin(), converted.end());
    return true;
}


bool Foam::restartState::readBodyNodes
(
    std::vector<label>& nodes,
    std::vector<label>& bodies
) const
{
    IOobject aIO(file("bodyNodes", IOobject::MUST_READ));
    if (!aIO.typeHeaderOk<labelIOList>(true)) return false;
    const labelIOList pairs(aIO);
    nodes.clear();
    bodies.clear();
    for (label i = 0; i + 1 < pairs.size(); i += 2)
    {
        nodes.push_back(pairs[i]);
        bodies.push_back(pairs[i + 1]);
    }
    Info<< "Restart: read the element nodes on the rigid bodies from "
        << aIO.objectPath() << nl;
    return true;
}


bool Foam::restartState::readBodies(rigidBodies& bodies) const
{
    IOobject bIO(file("rigidBodies", IOobject::MUST_READ));
    if (!bIO.typeHeaderOk<IOdictionary>(true)) return false;
    bodies.readState(IOdictionary(bIO));
    Info<< "Restart: read the rigid bodies' state from " << bIO.objectPath()
        << nl;
    return true;
}


// ************************************************************************* //
