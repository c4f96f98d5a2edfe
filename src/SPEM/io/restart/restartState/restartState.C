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
#include <cmath>
#include <sstream>

namespace
{
    //- The folder of a state, the folder it is written in, its file list
    const Foam::word stateDir("spem");
    const Foam::word writingDir("spem.writing");
    const Foam::word manifest("restartFiles");

    bool isFinite(const Foam::scalar s) { return std::isfinite(s); }
    bool isFinite(const Foam::vector& v)
    {
        return std::isfinite(v.x()) && std::isfinite(v.y());
    }
    bool isPositive(const Foam::scalar s) { return s > 0; }
    bool isPositive(const Foam::vector&) { return true; }
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::IOobject Foam::restartState::file(const word& name) const
{
    return IOobject
    (
        name, runTime_.timeName(), stateDir, runTime_, IOobject::MUST_READ,
        IOobject::NO_WRITE, false
    );
}


Foam::IOobject Foam::restartState::outFile(const word& name) const
{
    return IOobject
    (
        name, runTime_.timeName(), writingDir, runTime_, IOobject::NO_READ,
        IOobject::NO_WRITE, false
    );
}


void Foam::restartState::writeExact
(
    const regIOobject& io,
    const bool ascii
) const
{
    OFstream os
    (
        io.objectPath(),
        ascii ? IOstream::ASCII : format(),
        IOstream::currentVersion,
        runTime_.writeCompression()
    );
    // All the digits of a double: the restart continues bit for bit
    os.precision(17);
    io.writeHeader(os);
    io.writeData(os);
    IOobject::writeEndDivider(os);
    if (!os.good())
    {
        FatalErrorInFunction
            << "Could not write " << io.objectPath() << exit(FatalError);
    }
    written_.append(io.name());
}


Foam::IOstream::streamFormat Foam::restartState::format() const
{
    // Binary unless the case asks for ascii: 17 digits of text per double
    // were most of the time a write took (issue 18)
    return runTime_.controlDict().found("writeFormat")
        ? runTime_.writeFormat() : IOstream::BINARY;
}


template<class Type>
bool Foam::restartState::listed(const IOobject& io) const
{
    if (!startFiles_.found(io.name())) return false;
    IOobject header(io);
    if (!header.typeHeaderOk<Type>(true))
    {
        bad(io, "empty, truncated or not an OpenFOAM file");
    }
    return true;
}


void Foam::restartState::bad(const IOobject& io, const std::string& why) const
{
    FatalErrorInFunction
        << "Restart state " << io.objectPath() << ": " << why.c_str() << nl
        << "    Remove time " << runTime_.timeName()
        << " to start from the time before it, or set restartFallback yes"
        << " in controlDict." << exit(FatalError);
    std::abort();
}


template<class Type>
void Foam::restartState::checkValues
(
    const IOobject& io,
    const Field<Type>& f,
    const bool mustBePositive
) const
{
    forAll(f, i)
    {
        if (!isFinite(f[i]))
        {
            bad(io, "entry " + std::to_string(i) + " is not finite");
        }
        if (mustBePositive && !isPositive(f[i]))
        {
            bad(io, "entry " + std::to_string(i) + " is not positive");
        }
    }
}


void Foam::restartState::checkPositions
(
    const IOobject& io,
    const vectorField& x
) const
{
    const bounds& b = bounds_;
    forAll(x, i)
    {
        if
        (
            x[i].x() < b.boxMin[0] || x[i].x() > b.boxMax[0]
         || x[i].y() < b.boxMin[1] || x[i].y() > b.boxMax[1]
        )
        {
            std::ostringstream os;
            os  << "entry " << i << ", position (" << x[i].x() << ' '
                << x[i].y() << "), is outside the box [(" << b.boxMin[0]
                << ' ' << b.boxMin[1] << "), (" << b.boxMax[0] << ' '
                << b.boxMax[1] << ")], the mesh enlarged by 1000 times"
                << " its size, which no particle of a valid state leaves";
            bad(io, os.str());
        }
    }
}


void Foam::restartState::checkSpeeds
(
    const IOobject& io,
    const vectorField& v
) const
{
    forAll(v, i)
    {
        // Scaled: a component of 1e300 must not overflow its square
        const scalar s = max(mag(v[i].x()), mag(v[i].y()));
        const scalar speed =
            s > 0 ? s*std::sqrt(sqr(v[i].x()/s) + sqr(v[i].y()/s)) : 0;
        if (!(speed < bounds_.maxSpeed))
        {
            std::ostringstream os;
            os  << "entry " << i << ", speed " << speed << " m/s, is not below"
                << " the fastest wave speed of the case, "
                << bounds_.maxSpeed << " m/s (Mach < 1)";
            bad(io, os.str());
        }
    }
}


void Foam::restartState::checkBetween
(
    const IOobject& io,
    const scalarField& f,
    const scalar lower,
    const scalar upper,
    const std::string& why
) const
{
    forAll(f, i)
    {
        if (!(f[i] >= lower && f[i] <= upper))
        {
            std::ostringstream os;
            os  << "entry " << i << ", " << f[i] << ", is outside ["
                << lower << ", " << upper << "]: " << why;
            bad(io, os.str());
        }
    }
}


void Foam::restartState::writeParticles(const sphFluid& particles) const
{
    const particleSet& ps = particles.particles();
    const label nFluid = particles.nFluid();
    const IOobject xIO(outFile("particlePositions"));
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
    for (const regIOobject* f : {&xf, &vf})
    {
        writeExact(*f);
    }
    for (const regIOobject* f : {&rho, &rhoOld, &m, &h})
    {
        writeExact(*f);
    }
    // The level only where it is not 0 everywhere: a state of one
    // resolution stays as it was without the multi-resolution SPEM
    labelIOList level(IOobject(xIO, "particleLevel"), nFluid);
    bool refined = false;
    forAll(level, k)
    {
        level[k] = ps.level()[order[k]];
        refined = refined || level[k] != 0;
    }
    if (refined) writeExact(level);

    // The storage order the next evaluation starts from: fluid particle k
    // of the files above is k, wall particle r (by id) is nFluid + r
    std::vector<label> code(ps.size(), -1);
    forAll(xf, k) code[order[k]] = k;
    std::vector<label> walls;
    for (label i = 0; i < ps.size(); ++i)
    {
        if (particleSet::isWall(ps.kinds()[i])
         && ps.kinds()[i] != particleSet::kind::structure)
        {
            walls.push_back(i);
        }
    }
    std::sort
    (
        walls.begin(), walls.end(),
        [&](const label a, const label b) { return ps.id()[a] < ps.id()[b]; }
    );
    forAll(walls, r) code[walls[r]] = nFluid + r;
    std::vector<label> evaluation;
    particles.evaluationOrder(evaluation);
    IOdictionary storage(outFile("particleOrder"));
    labelList slots(label(evaluation.size()));
    forAll(slots, s) slots[s] = code[evaluation[s]];
    storage.add("order", slots);
    storage.add("stepsSinceSort", particles.stepsSinceReorder());
    writeExact(storage, true);
}


void Foam::restartState::writeAcceleration
(
    const word& name,
    const wallAcceleration& wa
) const
{
    const IOobject uIO(outFile(name + "OldU"));
    vectorIOField U(uIO, wa.size());
    vectorIOField A(IOobject(uIO, name + "Acceleration"), wa.size());
    forAll(U, k)
    {
        U[k] = vector(wa.oldVelocities()[2*k], wa.oldVelocities()[2*k + 1], 0);
        A[k] = vector(wa.accelerations()[2*k], wa.accelerations()[2*k + 1], 0);
    }
    writeExact(U);
    writeExact(A);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::restartState::restartState(const Time& runTime)
:
    runTime_(runTime)
{
    const fileName dir = startPath();
    if (!isDir(dir))
    {
        if (runTime.value() == 0) return;     // a fresh start
        FatalIOErrorInFunction(runTime.controlDict())
            << "Start time " << runTime.timeName() << " (startFrom "
            << runTime.controlDict().getOrDefault<word>("startFrom", "startTime")
            << ") has no restart state " << dir << ": its write was"
            << " interrupted, or no run wrote that time." << nl
            << "    Remove " << runTime.timePath() << " (or set startTime to"
            << " a time that was written, or restartFallback yes in"
            << " controlDict) to continue from an earlier time."
            << exit(FatalIOError);
    }
    IOobject mIO(file(manifest));
    if (!mIO.typeHeaderOk<IOdictionary>(true))
    {
        FatalErrorInFunction
            << "Restart state " << dir << " has no " << manifest
            << " (the list of its files): it was written by an earlier"
            << " version or edited by hand. Remove time "
            << runTime.timeName() << " to start from the time before it"
            << " (or set restartFallback yes in controlDict)"
            << exit(FatalError);
    }
    startFiles_ = IOdictionary(mIO).get<wordList>("files");
    for (const word& name : startFiles_)
    {
        if (!isFile(dir/name) && !isFile(dir/(name + ".gz")))
        {
            bad(file(name), "missing (" + manifest + " lists it)");
        }
    }
    if (startFiles_.empty())
    {
        bad(mIO, "lists no files");
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::fileName Foam::restartState::startPath() const
{
    return runTime_.timePath()/stateDir;
}


void Foam::restartState::write(const content& c) const
{
    const fileName writing = runTime_.timePath()/writingDir;
    if (isDir(writing)) rmDir(writing);
    mkDir(writing);
    written_.clear();

    if (c.particles) writeParticles(*c.particles);
    if (c.virtualParticles)
    {
        writeAcceleration("virtualParticle", *c.virtualParticles);
    }
    if (c.bodyParticles) writeAcceleration("bodyParticle", *c.bodyParticles);
    if (c.previousDeltaT >= 0)
    {
        IOdictionary step(outFile("timeStep"));
        step.add("previousDeltaT", c.previousDeltaT);
        if (c.previousSubStep >= 0)
        {
            step.add("previousSubStep", c.previousSubStep);
        }
        writeExact(step, true);
    }
    if (c.solidFluidLoad && !c.solidFluidLoad->empty())
    {
        const std::vector<scalar>& F = *c.solidFluidLoad;
        vectorIOField load(outFile("solidFluidLoad"), label(F.size()/2));
        forAll(load, i) load[i] = vector(F[2*i], F[2*i + 1], 0);
        writeExact(load);
    }
    if (c.bodies && !c.bodies->empty())
    {
        IOdictionary state(outFile("rigidBodies"));
        c.bodies->writeState(state);
        writeExact(state, true);
    }
    if (c.bodyNodes)
    {
        const bodyElementCoupling& be = *c.bodyNodes;
        labelIOList pairs(outFile("bodyNodes"), 2*be.size());
        for (label k = 0; k < be.size(); ++k)
        {
            pairs[2*k] = be.nodes()[k];
            pairs[2*k + 1] = be.bodies()[k];
        }
        writeExact(pairs);
    }
    if (c.convertedTriangles && !c.convertedTriangles->empty())
    {
        const std::vector<label>& t = *c.convertedTriangles;
        labelIOList converted(outFile("convertedTriangles"), label(t.size()));
        forAll(converted, i) converted[i] = t[i];
        writeExact(converted);
    }
    if (c.elements)
    {
        const std::vector<scalar>& x = c.elements->positions();
        const std::vector<scalar>& v = c.elements->velocities();
        const label n = c.elements->nNodes();
        vectorIOField xf(outFile("points"), n);
        vectorIOField vf(outFile("U"), n);
        for (label i = 0; i < n; ++i)
        {
            xf[i] = vector(x[2*i], x[2*i + 1], 0);
            vf[i] = vector(v[2*i], v[2*i + 1], 0);
        }
        writeExact(xf);
        writeExact(vf);
    }

    // The list last, then the rename: a state is there whole or not at all
    IOdictionary list(outFile(manifest));
    list.add("files", wordList(written_));
    writeExact(list, true);
    const fileName dir = runTime_.timePath()/stateDir;
    if (isDir(dir)) rmDir(dir);
    if (!mv(writing, dir))
    {
        FatalErrorInFunction
            << "Could not rename " << writing << " to " << dir
            << exit(FatalError);
    }
}


bool Foam::restartState::readElements(elementModel& elements) const
{
    const IOobject xIO(file("points"));
    if (!listed<vectorIOField>(xIO))
    {
        if (restarting())
        {
            bad(xIO, "missing: the case has elements, the state none"
                " (written by another method or mesh?)");
        }
        return false;
    }
    const IOobject vIO(file("U"));
    if (!listed<vectorIOField>(vIO)) bad(vIO, "missing");
    const vectorIOField xf(xIO);
    const vectorIOField vf(vIO);
    const label nNodes = elements.nNodes();
    if (xf.size() != nNodes || vf.size() != nNodes)
    {
        bad
        (
            xIO,
            std::to_string(xf.size()) + " points and "
          + std::to_string(vf.size()) + " velocities; the mesh has "
          + std::to_string(nNodes) + " nodes"
        );
    }
    checkValues(xIO, xf);
    checkValues(vIO, vf);
    checkPositions(xIO, xf);
    checkSpeeds(vIO, vf);
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
    const IOobject xIO(file("particlePositions"));
    if (!listed<vectorIOField>(xIO)) return false;
    const word names[] =
        {"particleU", "particleRho", "particleRhoOld", "particleMass",
         "particleH"};
    for (const word& name : names)
    {
        const IOobject io(file(name));
        if (name == "particleU" ? !listed<vectorIOField>(io)
                                : !listed<scalarIOField>(io))
        {
            bad(io, "missing");
        }
    }
    const vectorIOField xf(xIO);
    const vectorIOField vf(file("particleU"));
    const scalarIOField rho(file("particleRho"));
    const scalarIOField old(file("particleRhoOld"));
    const scalarIOField m(file("particleMass"));
    const scalarIOField h(file("particleH"));
    const label n = xf.size();
    for (const label size : {vf.size(), rho.size(), old.size(), m.size(), h.size()})
    {
        if (size != n)
        {
            bad
            (
                xIO,
                "inconsistent: " + std::to_string(n) + " positions, "
              + std::to_string(vf.size()) + " velocities, "
              + std::to_string(rho.size()) + " densities, "
              + std::to_string(old.size()) + " old densities, "
              + std::to_string(m.size()) + " masses, "
              + std::to_string(h.size()) + " smoothing lengths"
            );
        }
    }
    checkValues(xIO, xf);
    checkValues(vf, vf);
    checkValues(rho, rho, true);
    checkValues(old, old, true);
    checkValues(m, m, true);
    checkValues(h, h, true);
    checkPositions(xIO, xf);
    checkSpeeds(vf, vf);
    const bounds& b = bounds_;
    if (b.rho0 > 0)
    {
        const std::string why =
            "a density beyond a factor of 2 from rho0 would take a flow at"
            " Mach ~1 to make";
        checkBetween(rho, rho, 0.5*b.rho0, 2*b.rho0, why);
        checkBetween(old, old, 0.5*b.rho0, 2*b.rho0, why);
        const scalar dx = b.boxMax[0] - b.boxMin[0];
        const scalar dy = b.boxMax[1] - b.boxMin[1];
        checkBetween
        (
            m, m, 0, 2*b.rho0*dx*dy,
            "more than 2 rho0 times the area of the box of the positions"
        );
        checkBetween
        (
            h, h, 0, std::sqrt(dx*dx + dy*dy),
            "larger than the diagonal of the box of the positions"
        );
    }

    labelList level(n, 0);
    const IOobject levelIO(file("particleLevel"));
    if (listed<labelIOList>(levelIO))
    {
        level = labelIOList(levelIO);
        if (level.size() != n)
        {
            bad
            (
                levelIO,
                "inconsistent: " + std::to_string(level.size())
              + " levels for " + std::to_string(n) + " positions"
            );
        }
        for (const label l : level)
        {
            if (l < 0 || l > 255)
            {
                bad(levelIO, "a level outside [0, 255]: " + std::to_string(l));
            }
        }
    }

    particles.reserve(n);
    forAll(xf, i)
    {
        particles.append
        (
            xf[i].x(), xf[i].y(), vf[i].x(), vf[i].y(), rho[i], 0, m[i], h[i],
            particleSet::kind::fluid, static_cast<unsigned char>(level[i])
        );
    }
    // Densities at the start of the step (volumes of the next evaluation)
    rhoOld.assign(old.begin(), old.end());
    Info<< "Restart: read " << n << " fluid particles from " << xIO.path()
        << nl << endl;
    return true;
}


bool Foam::restartState::readParticleOrder
(
    const particleSet& particles,
    std::vector<label>& newToOld,
    label& stepsSinceSort
) const
{
    const IOobject io(file("particleOrder"));
    if (!listed<IOdictionary>(io)) return false;
    const IOdictionary storage(io);
    const labelList slots(storage.get<labelList>("order"));
    stepsSinceSort = storage.get<label>("stepsSinceSort");

    // Fluid particles and walls, each in the order of their ids
    std::vector<label> fluid, walls;
    for (label i = 0; i < particles.size(); ++i)
    {
        const particleSet::kind k = particles.kinds()[i];
        if (k == particleSet::kind::fluid) fluid.push_back(i);
        else if (k == particleSet::kind::wall || k == particleSet::kind::slipWall)
        {
            walls.push_back(i);
        }
    }
    const auto byId = [&](const label a, const label b)
    {
        return particles.id()[a] < particles.id()[b];
    };
    std::sort(fluid.begin(), fluid.end(), byId);
    std::sort(walls.begin(), walls.end(), byId);
    const label nFluid = label(fluid.size());
    const label n = nFluid + label(walls.size());
    if (slots.size() != n || stepsSinceSort < 0)
    {
        bad
        (
            io,
            std::to_string(slots.size()) + " slots for "
          + std::to_string(nFluid) + " fluid and "
          + std::to_string(walls.size()) + " wall particles"
        );
    }
    std::vector<bool> seen(n, false);
    newToOld.resize(n);
    forAll(slots, s)
    {
        const label c = slots[s];
        if (c < 0 || c >= n || seen[c])
        {
            bad(io, "slot " + std::to_string(s) + " is out of range or repeated");
        }
        seen[c] = true;
        newToOld[s] = c < nFluid ? fluid[c] : walls[c - nFluid];
    }
    return true;
}


void Foam::restartState::readAcceleration
(
    const word& name,
    wallAcceleration& wa
) const
{
    const IOobject uIO(file(name + "OldU"));
    if (!listed<vectorIOField>(uIO)) return;
    const IOobject aIO(file(name + "Acceleration"));
    if (!listed<vectorIOField>(aIO)) bad(aIO, "missing");
    const vectorIOField U(uIO);
    const vectorIOField A(aIO);
    if (U.size() != wa.size() || A.size() != wa.size())
    {
        bad
        (
            uIO,
            std::to_string(U.size()) + " moving wall particles; the case has "
          + std::to_string(wa.size()) + ". Is the state from another mesh or"
            " body set-up? (Allclean removes it.)"
        );
    }
    checkValues(uIO, U);
    checkValues(aIO, A);
    checkSpeeds(uIO, U);
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
    const IOobject cIO(file("convertedTriangles"));
    if (!listed<labelIOList>(cIO)) return false;
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
    const IOobject aIO(file("bodyNodes"));
    if (!listed<labelIOList>(aIO)) return false;
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
    const IOobject bIO(file("rigidBodies"));
    if (!listed<IOdictionary>(bIO)) return false;
    bodies.readState(IOdictionary(bIO));
    Info<< "Restart: read the rigid bodies' state from " << bIO.objectPath()
        << nl;
    return true;
}


Foam::scalar Foam::restartState::readPreviousDeltaT() const
{
    if (!restarting()) return 0;
    const IOobject io(file("timeStep"));
    if (!listed<IOdictionary>(io))
    {
        bad(io, "missing: the state has no step history");
    }
    const scalar dt = IOdictionary(io).get<scalar>("previousDeltaT");
    // The steps before the state sum to its time: none is longer
    if (!(std::isfinite(dt) && dt >= 0 && dt <= runTime_.value()*(1 + 1e-9)))
    {
        bad
        (
            io,
            "previousDeltaT is not a step of the run: not finite, negative"
            " or longer than the time of the state"
        );
    }
    return dt;
}


bool Foam::restartState::readSolidFluidLoad(std::vector<scalar>& load) const
{
    load.clear();
    if (!restarting()) return false;
    const IOobject io(file("solidFluidLoad"));
    if (!listed<vectorIOField>(io)) return false;
    const vectorIOField F(io);
    load.resize(2*F.size());
    forAll(F, i)
    {
        load[2*i] = F[i].x();
        load[2*i + 1] = F[i].y();
        if (!std::isfinite(load[2*i]) || !std::isfinite(load[2*i + 1]))
        {
            bad(io, "a load that is not finite");
        }
    }
    return true;
}


Foam::scalar Foam::restartState::readPreviousSubStep() const
{
    if (!restarting()) return -1;
    const IOobject io(file("timeStep"));
    if (!listed<IOdictionary>(io)) return -1;
    const IOdictionary step(io);
    if (!step.found("previousSubStep")) return -1;
    const scalar dt = step.get<scalar>("previousSubStep");
    if
    (
        !(std::isfinite(dt) && dt >= 0 && dt <= runTime_.value()*(1 + 1e-9))
    )
    {
        bad
        (
            io,
            "previousSubStep is not a sub-step of the run: not finite,"
            " negative or longer than the time of the state"
        );
    }
    return dt;
}


// ************************************************************************* //
