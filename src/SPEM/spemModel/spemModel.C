#include "spemModel.H"
#include "Time.H"
#include "vectorIOField.H"
#include "uniformDimensionedFields.H"
#include "OSspecific.H"
#include "vtkSeriesWriter.H"
#include "checkKeywords.H"

#include <cmath>
#include <stdexcept>

namespace Foam
{
    defineTypeNameAndDebug(spemModel, 0);
}

const Foam::Enum<Foam::spemModel::methodType>
Foam::spemModel::methodTypeNames
({
    { methodType::SPEM, "SPEM" },
    { methodType::SPH, "SPH" },
    { methodType::multiResolutionSPEM, "multiResolutionSPEM" },
});


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::PtrList<Foam::spemMaterial> Foam::spemModel::readMaterials() const
{
    const dictionary& regionsDict = subDict("regions");

    // Every entry must name a mesh region (catches misspelt zone names)
    for (const entry& e : regionsDict)
    {
        if (mesh_.findRegion(e.keyword()) < 0)
        {
            FatalIOErrorInFunction(regionsDict)
                << "Region '" << e.keyword() << "' is not a region of the"
                << " mesh. Mesh regions (cellZones): " << mesh_.regionNames()
                << exit(FatalIOError);
        }
    }

    PtrList<spemMaterial> materials(mesh_.nRegions());
    forAll(mesh_.regionNames(), r)
    {
        const word& name = mesh_.regionNames()[r];
        if (!regionsDict.isDict(name))
        {
            FatalIOErrorInFunction(regionsDict)
                << "Missing sub-dictionary 'regions/" << name
                << "': every mesh region needs a material"
                << exit(FatalIOError);
        }
        materials.set(r, spemMaterial::New(name, regionsDict.subDict(name)));
    }
    return materials;
}


void Foam::spemModel::readBoundaries()
{
    const dictionary& bcDict = subDict("boundaries");
    for (const entry& e : bcDict)
    {
        if (mesh_.findPatch(e.keyword()) < 0)
        {
            FatalIOErrorInFunction(bcDict)
                << "Patch '" << e.keyword() << "' is not a patch of the mesh."
                << " Mesh patches: " << mesh_.patchNames()
                << exit(FatalIOError);
        }
    }

    patchTypes_.setSize(mesh_.nPatches());
    forAll(mesh_.patchNames(), p)
    {
        const word& name = mesh_.patchNames()[p];
        if (!bcDict.isDict(name))
        {
            FatalIOErrorInFunction(bcDict)
                << "Missing sub-dictionary 'boundaries/" << name
                << "': every mesh patch needs a condition, one of "
                << patchTypeNames << exit(FatalIOError);
        }
        checkKeywords(bcDict.subDict(name), {"type"});
        patchTypes_[p] = patchTypeNames.get("type", bcDict.subDict(name));
    }

    // Two slip walls meeting at more than this angle make a corner
    std::vector<elementModel::constraint> c;
    std::vector<scalar> normal;
    nodeConstraints
    (
        mesh_, patchTypes_, getOrDefault<scalar>("slipCornerAngle", 10),
        c, normal
    );
    elements_->setConstraints(std::move(c), std::move(normal));
}


void Foam::spemModel::readGravity()
{
    IOobject gIO
    (
        "g",
        runTime_.constant(),
        runTime_,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    if (!gIO.typeHeaderOk<uniformDimensionedVectorField>(true))
    {
        Info<< "No constant/g: no gravity" << nl;
        return;
    }
    const uniformDimensionedVectorField g(gIO);
    if (mag(g.value().z()) > SMALL*mag(g.value()))
    {
        FatalErrorInFunction
            << "Gravity in " << gIO.objectPath() << " must lie in the x-y"
            << " plane of the 2D mesh, found " << g.value()
            << exit(FatalError);
    }
    elements_->setGravity(g.value().x(), g.value().y());
}


void Foam::spemModel::readState()
{
    IOobject xIO
    (
        "points", runTime_.timeName(), "spem", runTime_,
        IOobject::MUST_READ, IOobject::NO_WRITE, false
    );
    if (!xIO.typeHeaderOk<vectorIOField>(true)) return;

    IOobject vIO(xIO, "U");
    const vectorIOField xf(xIO);
    const vectorIOField vf(vIO);
    if (xf.size() != mesh_.nPoints() || vf.size() != mesh_.nPoints())
    {
        FatalErrorInFunction
            << "Restart state in " << xIO.path() << " has " << xf.size()
            << " points and " << vf.size() << " velocities; the mesh has "
            << mesh_.nPoints() << " nodes" << exit(FatalError);
    }
    std::vector<scalar> x(2*xf.size()), v(2*vf.size());
    forAll(xf, i)
    {
        x[2*i] = xf[i].x();
        x[2*i + 1] = xf[i].y();
        v[2*i] = vf[i].x();
        v[2*i + 1] = vf[i].y();
    }
    elements_->setState(x, v);
    Info<< "Restart: read node positions and velocities from "
        << xIO.path() << nl << endl;
}


void Foam::spemModel::writeState() const
{
    const std::vector<scalar>& x = elements_->positions();
    const std::vector<scalar>& v = elements_->velocities();
    const label n = elements_->nNodes();

    IOobject xIO
    (
        "points", runTime_.timeName(), "spem", runTime_,
        IOobject::NO_READ, IOobject::NO_WRITE, false
    );
    vectorIOField xf(xIO, n);
    vectorIOField vf(IOobject(xIO, "U"), n);
    for (label i = 0; i < n; ++i)
    {
        xf[i] = vector(x[2*i], x[2*i + 1], 0);
        vf[i] = vector(v[2*i], v[2*i + 1], 0);
    }
    mkDir(runTime_.timePath()/"spem");
    xf.write();
    vf.write();
}


void Foam::spemModel::writeVTK()
{
    const elementModel& em = *elements_;
    const label nNodes = em.nNodes(), nEl = em.nElements();
    const std::vector<scalar>& x = em.positions();
    const std::vector<scalar>& X = em.referencePositions();

    std::vector<scalar> displacement(2*nNodes);
    for (label i = 0; i < 2*nNodes; ++i) displacement[i] = x[i] - X[i];
    std::vector<scalar> regionId(nEl);
    for (label r = 0; r < em.regions().size(); ++r)
    {
        for (label e = em.regions()[r].elemBegin; e < em.regions()[r].elemEnd; ++e)
        {
            regionId[e] = r;
        }
    }
    const elementModel::elementFields f = em.fields();

    vtkOutput::triangleBlock elements;
    elements.name = "elements";
    elements.nPoints = nNodes;
    elements.points = x.data();
    elements.nTriangles = nEl;
    elements.triangles = em.elementNodes().data();
    elements.pointData =
    {
        {"velocity", 2, em.velocities().data()},
        {"displacement", 2, displacement.data()}
    };
    elements.cellData =
    {
        {"pressure", 1, f.pressure.data()},
        {"density", 1, f.density.data()},
        {"stress", 6, f.stress.data()},
        {"vonMisesStress", 1, f.vonMises.data()},
        {"region", 1, regionId.data()}
    };

    try
    {
        // Created at the first write: on restart it drops the entries of the
        // existing series from the start time on
        if (!vtk_)
        {
            vtk_.reset
            (
                new vtkOutput::seriesWriter
                (
                    runTime_.path()/"VTK",
                    runTime_.caseName().name(),
                    runTime_.value()
                )
            );
        }
        vtk_->write(runTime_.value(), {elements}, {});
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "Writing the VTK series failed: " << err.what()
            << exit(FatalError);
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::spemModel::spemModel(const Time& runTime)
:
    IOdictionary
    (
        IOobject
        (
            "spemProperties",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    runTime_(runTime),
    schemes_
    (
        IOobject
        (
            "spemSchemes",
            runTime.system(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    ),
    method_(methodTypeNames.get("method", schemes_)),
    mesh_(triMesh::read(runTime)),
    lastWrittenTime_(-GREAT)
{
    checkKeywords
    (
        *this, {"regions", "boundaries", "damping", "slipCornerAngle"}
    );
    checkKeywords(schemes_, {"method"});
    if (method_ != methodType::SPEM)
    {
        FatalIOErrorInFunction(schemes_)
            << "method " << methodTypeNames[method_]
            << " needs the particle half, which this version does not have"
            << " yet; use method SPEM" << exit(FatalIOError);
    }

    elements_.reset(new elementModel(mesh_, readMaterials()));
    readBoundaries();
    readGravity();

    const dictionary* dampingDict = findDict("damping");
    if (dampingDict) checkKeywords(*dampingDict, {"massProportional"});
    const scalar alpha =
        dampingDict
      ? dampingDict->getOrDefault<scalar>("massProportional", 0)
      : 0;
    if (alpha < 0)
    {
        FatalIOErrorInFunction(*dampingDict)
            << "massProportional must not be negative" << exit(FatalIOError);
    }
    elements_->setMassDamping(alpha);

    readState();

    Info<< "Mesh: " << mesh_.nPoints() << " nodes, " << mesh_.nTriangles()
        << " triangles, " << mesh_.nSegments() << " boundary segments" << nl;
    const elementModel& em = *elements_;
    for (const elementModel::region& r : em.regions())
    {
        const label ri = &r - em.regions().cdata();
        Info<< "    region " << r.name << ": "
            << em.material(ri).type() << ", "
            << r.elemEnd - r.elemBegin << " elements, "
            << r.domainEnd - r.domainBegin << " smoothing domains" << nl;
    }
    forAll(mesh_.patchNames(), p)
    {
        Info<< "    patch " << mesh_.patchNames()[p] << ": "
            << patchTypeNames[patchTypes_[p]] << nl;
    }
    if (alpha > 0)
    {
        Info<< "    mass-proportional damping " << alpha << " 1/s" << nl;
    }
    Info<< endl;
}


Foam::spemModel::~spemModel() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::spemModel::stopWithLastGoodState()
{
    const std::string why = elements_->failure();
    const scalar tFail = runTime_.value();

    // The failed state is the current one; the previous one is good
    Time& runTime = const_cast<Time&>(runTime_);
    if (runTime.timeIndex() > runTime.startTimeIndex())
    {
        elements_->revert();
        runTime.setTime(tFail - runTime.deltaTValue(), runTime.timeIndex() - 1);
        // Stresses of the good state for the output (it evaluated before)
        elements_->evaluate();
    }
    write(true);
    FatalErrorInFunction
        << "Run stopped at time " << tFail << ": " << why.c_str() << nl
        << "    The last good state (time " << runTime.timeName()
        << ") has been written to " << runTime.timePath()
        << " and VTK/." << nl
        << "    Reduce maxCo or deltaT, or check the set-up near the failure."
        << exit(FatalError);
}


void Foam::spemModel::evaluate()
{
    if (!elements_->evaluate()) stopWithLastGoodState();
}


void Foam::spemModel::advance()
{
    if (!elements_->advance(runTime_.deltaTValue())) stopWithLastGoodState();
}


void Foam::spemModel::write(const bool force)
{
    if (!force && !runTime_.writeTime()) return;
    if (runTime_.value() == lastWrittenTime_) return;
    lastWrittenTime_ = runTime_.value();
    writeState();
    writeVTK();
    if (force)
    {
        // Time's own record (uniform/time) for a restart from here
        const_cast<Time&>(runTime_).writeNow();
    }
}


void Foam::spemModel::report(Ostream& os) const
{
    os  << "elements = " << elements_->nElements()
        << ", nodes = " << elements_->nNodes()
        << ", particles = 0";
}


// ************************************************************************* //
