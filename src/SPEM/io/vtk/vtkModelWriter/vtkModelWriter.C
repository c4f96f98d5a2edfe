#include "vtkModelWriter.H"
#include "vtkSeriesWriter.H"
#include "elementModel.H"
#include "sphFluid.H"
#include "rigidBodies.H"
#include "mathematicalConstants.H"

#include <cmath>
#include <stdexcept>

namespace
{

using Foam::label;
using Foam::scalar;

//- Arrays of one write, alive until the series has written them
struct blockData
{
    std::vector<scalar> displacement, regionId;
    Foam::elementModel::elementFields elementFields;

    //- Fluid and wall particles (gathered: the set interleaves them in
    //  cell order)
    struct gathered
    {
        std::vector<scalar> x, v, p, rho, h, surface, level, id;
    } fluid, wall;

    std::vector<scalar> bodyX, bodyV, bodyIndex;
    std::vector<label> bodyTriangles;
};


Foam::vtkOutput::triangleBlock elementBlock
(
    const Foam::elementModel& em,
    blockData& d
)
{
    const label nNodes = em.nNodes(), nEl = em.nElements();
    const std::vector<scalar>& x = em.positions();
    const std::vector<scalar>& X = em.referencePositions();

    d.displacement.resize(2*nNodes);
    for (label i = 0; i < 2*nNodes; ++i) d.displacement[i] = x[i] - X[i];
    d.regionId.resize(nEl);
    for (label r = 0; r < em.regions().size(); ++r)
    {
        const Foam::elementModel::region& reg = em.regions()[r];
        for (label e = reg.elemBegin; e < reg.elemEnd; ++e)
        {
            d.regionId[e] = r;
        }
    }
    d.elementFields = em.fields();
    const Foam::elementModel::elementFields& f = d.elementFields;

    Foam::vtkOutput::triangleBlock b;
    b.name = "elements";
    b.nPoints = nNodes;
    b.points = x.data();
    b.nTriangles = nEl;
    b.triangles = em.elementNodes().data();
    b.pointData =
    {
        {"velocity", 2, em.velocities().data()},
        {"displacement", 2, d.displacement.data()}
    };
    b.cellData =
    {
        {"pressure", 1, f.pressure.data()},
        {"density", 1, f.density.data()},
        {"stress", 6, f.stress.data()},
        {"vonMisesStress", 1, f.vonMises.data()},
        {"region", 1, d.regionId.data(), true}
    };
    return b;
}


void gatherParticles(const Foam::sphFluid& sph, blockData& d)
{
    using Foam::particleSet;
    const particleSet& ps = sph.particles();
    for (label i = 0; i < ps.size(); ++i)
    {
        // Ghosts are the elements' state, which the elements show
        if (ps.kinds()[i] == particleSet::kind::ghost) continue;
        const bool fluid = ps.kinds()[i] == particleSet::kind::fluid;
        blockData::gathered& g = fluid ? d.fluid : d.wall;
        g.x.push_back(ps.positions()[2*i]);
        g.x.push_back(ps.positions()[2*i + 1]);
        g.v.push_back(ps.velocities()[2*i]);
        g.v.push_back(ps.velocities()[2*i + 1]);
        g.p.push_back(ps.pressure()[i]);
        g.rho.push_back(ps.density()[i]);
        g.h.push_back(ps.smoothingLength()[i]);
        g.surface.push_back(fluid && sph.freeSurface(i));
        g.level.push_back(ps.level()[i]);
        g.id.push_back(ps.id()[i]);
    }
}


Foam::vtkOutput::particleBlock fluidBlock(const blockData::gathered& g)
{
    Foam::vtkOutput::particleBlock b;
    b.name = "particles";
    b.nParticles = g.p.size();
    b.positions = g.x.data();
    b.pointData =
    {
        {"velocity", 2, g.v.data()},
        {"pressure", 1, g.p.data()},
        {"density", 1, g.rho.data()},
        {"freeSurface", 1, g.surface.data(), true},
        {"smoothingLength", 1, g.h.data()},
        {"level", 1, g.level.data(), true},
        {"id", 1, g.id.data(), true}
    };
    return b;
}


//- Walls: their pressure is the extrapolated one of the boundary
//  condition, useful to see the load on a wall
Foam::vtkOutput::particleBlock wallBlock(const blockData::gathered& g)
{
    Foam::vtkOutput::particleBlock b;
    b.name = "wallParticles";
    b.nParticles = g.p.size();
    b.positions = g.x.data();
    b.pointData =
    {
        {"pressure", 1, g.p.data()},
        {"density", 1, g.rho.data()},
        {"smoothingLength", 1, g.h.data()}
    };
    return b;
}

//- Keep only the fields named in selected (empty: all)
void select
(
    std::vector<Foam::vtkOutput::field>& fields,
    const Foam::wordHashSet& selected
)
{
    if (selected.empty()) return;
    std::vector<Foam::vtkOutput::field> kept;
    for (Foam::vtkOutput::field& f : fields)
    {
        if (selected.found(f.name)) kept.push_back(std::move(f));
    }
    fields = std::move(kept);
}


//- The vtkFormat names and what each selects
const Foam::wordList formatNames{"raw", "lz4", "zlib", "ascii"};
const Foam::vtkOutput::seriesWriter::format formatValues[] =
{
    Foam::vtkOutput::seriesWriter::format::raw,
    Foam::vtkOutput::seriesWriter::format::lz4,
    Foam::vtkOutput::seriesWriter::format::zlib,
    Foam::vtkOutput::seriesWriter::format::ascii
};

//- The vtkPrecision names and what each selects
const Foam::wordList precisionNames{"single", "double"};
const Foam::vtkOutput::seriesWriter::precision precisionValues[] =
{
    Foam::vtkOutput::seriesWriter::precision::float32,
    Foam::vtkOutput::seriesWriter::precision::float64
};


//- The index in names of the word entry key of controls (names[0] if
//  absent); a FatalIOError naming the file, the keyword and the valid
//  names if it is none of them
Foam::label readChoice
(
    const Foam::dictionary& controls,
    const Foam::word& key,
    const Foam::wordList& names
)
{
    using namespace Foam;
    const word choice(controls.getOrDefault<word>(key, names[0]));
    const label index = names.find(choice);
    if (index < 0)
    {
        FatalIOErrorInFunction(controls)
            << "Unknown " << key << " '" << choice << "' in "
            << controls.name() << nl << "Valid: " << names
            << exit(FatalIOError);
    }
    return index;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Static Data * * * * * * * * * * * * * * * //

const Foam::wordList Foam::vtkModelWriter::fieldNames
{
    "velocity", "displacement", "pressure", "density", "stress",
    "vonMisesStress", "region", "freeSurface", "smoothingLength", "level",
    "id", "body"
};


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::vtkModelWriter::makeBodyOutlines(const rigidBodies& bodies)
{
    if (!bodyOutline_.empty()) return;
    forAll(bodies, b)
    {
        // 96 points round a circle (its perimeter over 96); a polygon's
        // straight runs add points no triangle uses
        const rigidBodyShape& shape = bodies[b].shape();
        const scalar spacing =
            std::sqrt(constant::mathematical::pi*shape.area())/48;
        bodyOutline_.push_back(shape.surfacePoints(spacing));
        bodyOutlineTriangles_.push_back
        (
            rigidBodyShape::triangulate(bodyOutline_.back())
        );
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::vtkModelWriter::vtkModelWriter(const Time& runTime)
:
    runTime_(runTime),
    format_(vtkOutput::seriesWriter::format::raw),
    precision_(vtkOutput::seriesWriter::precision::float32)
{
    const dictionary& controls = runTime.controlDict();
    format_ = formatValues[readChoice(controls, "vtkFormat", formatNames)];
    precision_ =
        precisionValues[readChoice(controls, "vtkPrecision", precisionNames)];

    if (!controls.found("vtkFields")) return;
    const wordList selected(controls.get<wordList>("vtkFields"));
    if (selected.empty())
    {
        FatalIOErrorInFunction(controls)
            << "vtkFields in " << controls.name() << " is empty: name at"
            << " least one of " << fieldNames << " (or leave vtkFields out"
            << " to write all)" << exit(FatalIOError);
    }
    for (const word& name : selected)
    {
        if (!fieldNames.found(name))
        {
            FatalIOErrorInFunction(controls)
                << "Unknown field '" << name << "' in vtkFields of "
                << controls.name() << nl << "Valid fields: " << fieldNames
                << exit(FatalIOError);
        }
        fields_.insert(name);
    }
}


Foam::vtkModelWriter::~vtkModelWriter() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::vtkModelWriter::write
(
    const elementModel* elements,
    const sphFluid* particles,
    const rigidBodies& bodies
)
{
    blockData d;
    std::vector<vtkOutput::triangleBlock> triangleBlocks;
    std::vector<vtkOutput::particleBlock> particleBlocks;
    if (elements) triangleBlocks.push_back(elementBlock(*elements, d));
    if (particles)
    {
        gatherParticles(*particles, d);
        particleBlocks.push_back(fluidBlock(d.fluid));
        particleBlocks.push_back(wallBlock(d.wall));
    }

    // Rigid bodies: their outlines, moved, with the rigid velocity
    if (!bodies.empty())
    {
        makeBodyOutlines(bodies);
        forAll(bodies, b)
        {
            const rigidBody& body = bodies[b];
            const label offset = label(d.bodyX.size()/2);
            const std::vector<scalar>& X = bodyOutline_[b];
            for (size_t i = 0; i < X.size()/2; ++i)
            {
                const vector2D x =
                    body.toCurrent(vector2D(X[2*i], X[2*i + 1]));
                const vector2D v = body.velocityAt(x.x(), x.y());
                d.bodyX.push_back(x.x());
                d.bodyX.push_back(x.y());
                d.bodyV.push_back(v.x());
                d.bodyV.push_back(v.y());
            }
            for (const label n : bodyOutlineTriangles_[b])
            {
                d.bodyTriangles.push_back(offset + n);
            }
            d.bodyIndex.resize(d.bodyTriangles.size()/3, b);
        }
        vtkOutput::triangleBlock bb;
        bb.name = "rigidBodies";
        bb.nPoints = d.bodyX.size()/2;
        bb.points = d.bodyX.data();
        bb.nTriangles = d.bodyTriangles.size()/3;
        bb.triangles = d.bodyTriangles.data();
        bb.pointData = {{"velocity", 2, d.bodyV.data()}};
        bb.cellData = {{"body", 1, d.bodyIndex.data(), true}};
        triangleBlocks.push_back(std::move(bb));
    }

    for (vtkOutput::triangleBlock& b : triangleBlocks)
    {
        select(b.pointData, fields_);
        select(b.cellData, fields_);
    }
    for (vtkOutput::particleBlock& b : particleBlocks)
    {
        select(b.pointData, fields_);
    }

    try
    {
        if (!series_)
        {
            series_.reset
            (
                new vtkOutput::seriesWriter
                (
                    runTime_.path()/"VTK",
                    runTime_.caseName().name(),
                    runTime_.value(),
                    format_,
                    precision_
                )
            );
        }
        series_->write(runTime_.value(), triangleBlocks, particleBlocks);
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "Writing the VTK series failed: " << err.what()
            << exit(FatalError);
    }
}


// ************************************************************************* //
