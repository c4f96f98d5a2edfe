/*---------------------------------------------------------------------------*\
Description
    Unit tests of Foam::vtkOutput::seriesWriter: what is written is read
    back with VTK's own XML readers (the ones ParaView uses) and compared
    value by value; the collection file is parsed as XML; restart drops and
    keeps the right entries. If pvpython is on PATH, ParaView itself opens
    the series (skipped otherwise).

    No OpenFOAM header here: VTK and OpenFOAM headers clash (Log macro).

\*---------------------------------------------------------------------------*/

#include "vtkSeriesWriter.H"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>
#include <sys/wait.h>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using namespace Foam::vtkOutput;

namespace
{

// A small mesh: unit square as two triangles plus one triangle to the right
//
//  3 ------ 2
//  |      / | .
//  |    /   |   4
//  |  /     | .
//  0 ------ 1
const std::vector<double> meshPoints =
    {0, 0,  1, 0,  1, 1,  0, 1,  2, 0.5};
const std::vector<int> meshTriangles =
    {0, 1, 2,  0, 2, 3,  1, 4, 2};
const std::size_t nMeshPoints = 5;
const std::size_t nMeshTriangles = 3;


//- Fields of the small mesh at one time, distinct per time and per value
struct meshFields
{
    std::vector<double> pressure;       // cell scalar
    std::vector<double> displacement;   // point 2D vector
    std::vector<double> stress;         // cell symmetric tensor

    explicit meshFields(double time)
    {
        for (std::size_t t = 0; t < nMeshTriangles; ++t)
        {
            pressure.push_back(100*time + t + 0.25);
            for (int c = 0; c < 6; ++c)
            {
                stress.push_back(1000*time + 10*t + c + 0.5);
            }
        }
        for (std::size_t p = 0; p < nMeshPoints; ++p)
        {
            displacement.push_back(time + 0.1*p);
            displacement.push_back(-time - 0.01*p);
        }
    }

    triangleBlock block() const
    {
        return triangleBlock
        {
            "elements",
            nMeshPoints, meshPoints.data(),
            nMeshTriangles, meshTriangles.data(),
            {{"displacement", 2, displacement.data()}},
            {{"pressure", 1, pressure.data()}, {"stress", 6, stress.data()}}
        };
    }
};


//- One block of a multiblock file read back with VTK's reader
vtkSmartPointer<vtkMultiBlockDataSet> readMultiBlock(const fs::path& vtm)
{
    vtkNew<vtkXMLMultiBlockDataReader> reader;
    reader->SetFileName(vtm.c_str());
    reader->Update();
    return vtkMultiBlockDataSet::SafeDownCast(reader->GetOutputDataObject(0));
}


std::string blockName(vtkMultiBlockDataSet* blocks, unsigned i)
{
    if (!blocks->HasMetaData(i))
    {
        return "<no meta data>";
    }
    const char* name = blocks->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
    return name ? name : "<no name>";
}


//- (timestep, file) of each <DataSet> of a collection, parsed as XML
std::vector<std::pair<std::string, std::string>> readCollection
(
    const fs::path& pvd
)
{
    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(pvd.c_str());
    if (!parser->Parse())
    {
        ADD_FAILURE() << pvd << " does not parse as XML";
        return {};
    }
    vtkXMLDataElement* root = parser->GetRootElement();
    EXPECT_STREQ(root->GetName(), "VTKFile");
    EXPECT_STREQ(root->GetAttribute("type"), "Collection");
    vtkXMLDataElement* collection =
        root->FindNestedElementWithName("Collection");
    if (!collection)
    {
        ADD_FAILURE() << pvd << " has no <Collection>";
        return {};
    }
    std::vector<std::pair<std::string, std::string>> entries;
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i)
    {
        vtkXMLDataElement* e = collection->GetNestedElement(i);
        EXPECT_STREQ(e->GetName(), "DataSet");
        const char* timestep = e->GetAttribute("timestep");
        const char* file = e->GetAttribute("file");
        entries.emplace_back(timestep ? timestep : "", file ? file : "");
    }
    return entries;
}


using collectionEntries = std::vector<std::pair<std::string, std::string>>;


//- A fresh output folder per test below the test's working directory
class VtkSeries : public ::testing::Test
{
protected:

    fs::path dir;

    void SetUp() override
    {
        dir = fs::current_path()/"VtkSeries"
            /::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir);
    }

    fs::path pvd() const { return dir/"case.pvd"; }

    //- Write the small mesh at the given times with a fresh writer
    void writeSeries(const std::vector<double>& times, double startTime = 0)
    {
        seriesWriter writer(dir.string(), "case", startTime);
        for (const double t : times)
        {
            const meshFields fields(t);
            writer.write(t, {fields.block()}, {});
        }
    }
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * Tests * * * * * * * * * * * * * * * * * //

TEST_F(VtkSeries, roundTripsTriangleFields)
{
    writeSeries({0, 0.5});

    for (const auto& [index, time] : {std::pair<int, double>{0, 0}, {1, 0.5}})
    {
        SCOPED_TRACE("time " + std::to_string(time));
        const fs::path vtm =
            dir/("case_00000" + std::to_string(index) + ".vtm");
        ASSERT_TRUE(fs::exists(vtm)) << vtm;

        auto blocks = readMultiBlock(vtm);
        ASSERT_TRUE(blocks);
        ASSERT_EQ(blocks->GetNumberOfBlocks(), 1u);
        EXPECT_EQ(blockName(blocks, 0), "elements");

        auto* grid = vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(0));
        ASSERT_TRUE(grid) << "block 0 is not an unstructured grid";

        // Points, z = 0
        ASSERT_EQ(grid->GetNumberOfPoints(), vtkIdType(nMeshPoints));
        for (std::size_t p = 0; p < nMeshPoints; ++p)
        {
            double x[3];
            grid->GetPoint(vtkIdType(p), x);
            EXPECT_EQ(x[0], meshPoints[2*p]) << "point " << p;
            EXPECT_EQ(x[1], meshPoints[2*p + 1]) << "point " << p;
            EXPECT_EQ(x[2], 0.0) << "point " << p;
        }

        // Triangles, node order kept
        ASSERT_EQ(grid->GetNumberOfCells(), vtkIdType(nMeshTriangles));
        vtkNew<vtkIdList> nodes;
        for (std::size_t t = 0; t < nMeshTriangles; ++t)
        {
            EXPECT_EQ(grid->GetCellType(vtkIdType(t)), VTK_TRIANGLE);
            grid->GetCellPoints(vtkIdType(t), nodes);
            ASSERT_EQ(nodes->GetNumberOfIds(), 3);
            for (int i = 0; i < 3; ++i)
            {
                EXPECT_EQ(nodes->GetId(i), meshTriangles[3*t + i])
                    << "triangle " << t << " node " << i;
            }
        }

        const meshFields expected(time);

        // Cell scalar
        vtkDataArray* pressure = grid->GetCellData()->GetArray("pressure");
        ASSERT_TRUE(pressure);
        ASSERT_EQ(pressure->GetNumberOfComponents(), 1);
        ASSERT_EQ(pressure->GetNumberOfTuples(), vtkIdType(nMeshTriangles));
        for (std::size_t t = 0; t < nMeshTriangles; ++t)
        {
            EXPECT_EQ(pressure->GetComponent(t, 0), expected.pressure[t]);
        }

        // Point 2D vector, read back with three components, z = 0
        vtkDataArray* displacement =
            grid->GetPointData()->GetArray("displacement");
        ASSERT_TRUE(displacement);
        ASSERT_EQ(displacement->GetNumberOfComponents(), 3);
        ASSERT_EQ(displacement->GetNumberOfTuples(), vtkIdType(nMeshPoints));
        for (std::size_t p = 0; p < nMeshPoints; ++p)
        {
            EXPECT_EQ
            (
                displacement->GetComponent(p, 0), expected.displacement[2*p]
            );
            EXPECT_EQ
            (
                displacement->GetComponent(p, 1),
                expected.displacement[2*p + 1]
            );
            EXPECT_EQ(displacement->GetComponent(p, 2), 0.0);
        }

        // Cell symmetric tensor, ParaView's component order and names
        vtkDataArray* stress = grid->GetCellData()->GetArray("stress");
        ASSERT_TRUE(stress);
        ASSERT_EQ(stress->GetNumberOfComponents(), 6);
        ASSERT_EQ(stress->GetNumberOfTuples(), vtkIdType(nMeshTriangles));
        for (std::size_t t = 0; t < nMeshTriangles; ++t)
        {
            for (int c = 0; c < 6; ++c)
            {
                EXPECT_EQ(stress->GetComponent(t, c), expected.stress[6*t + c]);
            }
        }
        const char* names[6] = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};
        for (int c = 0; c < 6; ++c)
        {
            ASSERT_TRUE(stress->GetComponentName(c)) << "component " << c;
            EXPECT_STREQ(stress->GetComponentName(c), names[c]);
        }

        // Time for ParaView when the .vtm is opened alone
        vtkDataArray* timeValue = grid->GetFieldData()->GetArray("TimeValue");
        ASSERT_TRUE(timeValue);
        EXPECT_EQ(timeValue->GetComponent(0, 0), time);
    }
}


TEST_F(VtkSeries, everyFormatReadsBackWithTheSameValues)
{
    // Each vtkFormat of spemFoam (vtkModelWriter), read back with VTK's own
    // readers: every point, cell and array value exactly, the elements
    // (an unstructured grid) and a particle cloud (poly data)
    struct formatCase
    {
        seriesWriter::format format;
        std::string name;
        //- In the piece's header: the compressor or the ascii data mode
        std::string headerMark;
    };
    const std::vector<formatCase> formats =
    {
        {seriesWriter::format::raw, "raw", "format=\"appended\""},
        {seriesWriter::format::lz4, "lz4", "vtkLZ4DataCompressor"},
        {seriesWriter::format::zlib, "zlib", "vtkZLibDataCompressor"},
        {seriesWriter::format::ascii, "ascii", "format=\"ascii\""}
    };

    // Values with all 17 digits, which a text format must keep
    const std::vector<double> particleXY =
        {0.1, 0.2, 1.0/3.0, 2.0/7.0, -1e-300, 6.02214076e23};
    const std::vector<double> particleRho = {1000.0/3.0, 999.1, M_PI};
    const meshFields fields(0.1 + 0.2);

    // In both precisions: Float32 gives each double rounded to float
    for (const auto precision :
        {seriesWriter::precision::float64, seriesWriter::precision::float32})
    for (const formatCase& f : formats)
    {
        const bool single = precision == seriesWriter::precision::float32;
        const auto stored = [single](const double v)
        {
            return single ? double(float(v)) : v;
        };
        SCOPED_TRACE(f.name + (single ? " float32" : " float64"));
        const std::string baseName =
            "case_" + f.name + (single ? "_float32" : "_float64");
        const particleBlock cloud
        {
            "particles", 3, particleXY.data(),
            {{"density", 1, particleRho.data()}}
        };
        seriesWriter(dir.string(), baseName, 0, f.format, precision)
            .write(0.3, {fields.block()}, {cloud});

        const std::string stem = baseName + "_000000";
        for (const std::string piece : {"_0.vtu", "_1.vtp"})
        {
            std::ifstream is(dir/stem/(stem + piece));
            ASSERT_TRUE(is.good()) << piece;
            std::string head(4096, '\0');
            is.read(&head[0], head.size());
            EXPECT_NE(head.find(f.headerMark), std::string::npos)
                << piece << ":\n" << head.substr(0, 600);
            if (f.format == seriesWriter::format::raw)
            {
                EXPECT_EQ(head.find("compressor="), std::string::npos) << head;
            }
        }

        auto blocks = readMultiBlock(dir/(stem + ".vtm"));
        ASSERT_TRUE(blocks);
        ASSERT_EQ(blocks->GetNumberOfBlocks(), 2u);
        auto* grid = vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(0));
        ASSERT_TRUE(grid);
        ASSERT_EQ(grid->GetNumberOfPoints(), vtkIdType(nMeshPoints));
        for (std::size_t p = 0; p < nMeshPoints; ++p)
        {
            double x[3];
            grid->GetPoint(vtkIdType(p), x);
            EXPECT_EQ(x[0], stored(meshPoints[2*p]));
            EXPECT_EQ(x[1], stored(meshPoints[2*p + 1]));
        }
        ASSERT_EQ(grid->GetNumberOfCells(), vtkIdType(nMeshTriangles));
        vtkNew<vtkIdList> nodes;
        for (std::size_t t = 0; t < nMeshTriangles; ++t)
        {
            grid->GetCellPoints(vtkIdType(t), nodes);
            ASSERT_EQ(nodes->GetNumberOfIds(), 3);
            for (int i = 0; i < 3; ++i)
            {
                EXPECT_EQ(nodes->GetId(i), meshTriangles[3*t + i]);
            }
        }
        vtkDataArray* pressure = grid->GetCellData()->GetArray("pressure");
        vtkDataArray* stress = grid->GetCellData()->GetArray("stress");
        vtkDataArray* displacement =
            grid->GetPointData()->GetArray("displacement");
        ASSERT_TRUE(pressure && stress && displacement);
        for (std::size_t t = 0; t < nMeshTriangles; ++t)
        {
            EXPECT_EQ(pressure->GetComponent(t, 0), stored(fields.pressure[t]));
            for (int c = 0; c < 6; ++c)
            {
                EXPECT_EQ
                (
                    stress->GetComponent(t, c), stored(fields.stress[6*t + c])
                );
            }
        }
        for (std::size_t p = 0; p < nMeshPoints; ++p)
        {
            EXPECT_EQ
            (
                displacement->GetComponent(p, 0), stored(fields.displacement[2*p])
            );
            EXPECT_EQ
            (
                displacement->GetComponent(p, 1),
                stored(fields.displacement[2*p + 1])
            );
            EXPECT_EQ(displacement->GetComponent(p, 2), 0.0);
        }
        vtkDataArray* timeValue = grid->GetFieldData()->GetArray("TimeValue");
        ASSERT_TRUE(timeValue);
        EXPECT_EQ(timeValue->GetComponent(0, 0), 0.3);

        auto* particles = vtkPolyData::SafeDownCast(blocks->GetBlock(1));
        ASSERT_TRUE(particles);
        ASSERT_EQ(particles->GetNumberOfPoints(), 3);
        ASSERT_EQ(particles->GetNumberOfVerts(), 3);
        vtkDataArray* rho = particles->GetPointData()->GetArray("density");
        ASSERT_TRUE(rho);
        for (vtkIdType p = 0; p < 3; ++p)
        {
            double x[3];
            particles->GetPoint(p, x);
            EXPECT_EQ(x[0], stored(particleXY[2*p])) << "particle " << p;
            EXPECT_EQ(x[1], stored(particleXY[2*p + 1])) << "particle " << p;
            EXPECT_EQ(rho->GetComponent(p, 0), stored(particleRho[p]));
        }
    }
}


TEST_F(VtkSeries, compareStatesFindsEveryFormatEqualInValueAndAChangedValueDifferent)
{
    // bin/tools/compareStates (the refactor check, src/SPEM/README.md)
    // reads VTK pieces in every vtkFormat and both precisions: the same
    // blocks written raw and in lz4, zlib or ascii compare equal in value;
    // one value changed by the least a Float32 can show compares different
    // (fails without foamStateFiles.py's skip of the ascii pieces'
    // InformationKey blocks, checked)
    const std::vector<double> particleXY =
        {0.1, 0.2, 1.0/3.0, 2.0/7.0, -1e-300, 6.02214076e23};
    const std::vector<double> particleRho = {1000.0/3.0, 999.1, M_PI};
    const meshFields fields(0.1 + 0.2);
    const auto write =
        [&](const fs::path& root, const std::string& name,
            const seriesWriter::format format,
            const seriesWriter::precision precision, const double* rho)
        {
            const particleBlock cloud
            {
                "particles", 3, particleXY.data(), {{"density", 1, rho}}
            };
            seriesWriter(fs::path(root/name/"VTK").string(), "case", 0, format, precision)
                .write(0.3, {fields.block()}, {cloud});
        };
    const auto compareStates = [&](const fs::path& a, const fs::path& b)
    {
        const fs::path out = dir/"compareStates.log";
        const std::string command =
            "/usr/bin/python3 " + std::string(SPEM_PROJECT_DIR)
          + "/bin/tools/compareStates " + a.string() + " " + b.string()
          + " > " + out.string() + " 2>&1";
        const int status = std::system(command.c_str());
        std::ifstream is(out);
        std::stringstream text;
        text << is.rdbuf();
        std::cout << text.str();
        return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str());
    };
    std::vector<double> changed = particleRho;
    changed[1] = double(std::nextafter(float(changed[1]), 2000.0f));
    for (const auto precision :
        {seriesWriter::precision::float64, seriesWriter::precision::float32})
    {
        const std::string p =
            precision == seriesWriter::precision::float32 ? "float32" : "float64";
        SCOPED_TRACE(p);
        for
        (
            const auto& [format, name] :
            {
                std::pair<seriesWriter::format, std::string>
                {seriesWriter::format::lz4, "lz4"},
                {seriesWriter::format::zlib, "zlib"},
                {seriesWriter::format::ascii, "ascii"}
            }
        )
        {
            write(dir/("raw_" + p), name, seriesWriter::format::raw, precision, particleRho.data());
            write(dir/("other_" + p), name, format, precision, particleRho.data());
            write(dir/("changed_" + p), name, format, precision, changed.data());
        }
        const auto same = compareStates(dir/("raw_" + p), dir/("other_" + p));
        EXPECT_EQ(same.first, 0) << same.second;
        EXPECT_NE(same.second.find("3 cases, all identical"), std::string::npos)
            << same.second;
        const auto different = compareStates(dir/("raw_" + p), dir/("changed_" + p));
        EXPECT_EQ(different.first, 1) << different.second;
        EXPECT_NE(different.second.find("PointData/density"), std::string::npos)
            << different.second;
    }
}


TEST_F(VtkSeries, collectionListsEveryTimeWrittenAndParsesAsXml)
{
    writeSeries({0, 0.5});

    ASSERT_TRUE(fs::exists(pvd()));
    EXPECT_FALSE(fs::exists(dir/"case.pvd.tmp")) << "temporary left behind";
    const collectionEntries expected =
        {{"0", "case_000000.vtm"}, {"0.5", "case_000001.vtm"}};
    EXPECT_EQ(readCollection(pvd()), expected);

    // Every listed file and its piece folder exist
    for (const auto& e : expected)
    {
        EXPECT_TRUE(fs::exists(dir/e.second)) << e.second;
        EXPECT_TRUE(fs::is_directory(dir/fs::path(e.second).stem()))
            << e.second;
    }
}


TEST_F(VtkSeries, collectionKeepsTimesToFullPrecision)
{
    const double awkward = 0.1 + 0.2;       // 0.30000000000000004
    writeSeries({1e-7, awkward, 12345.678});

    const collectionEntries entries = readCollection(pvd());
    ASSERT_EQ(entries.size(), 3u);
    EXPECT_EQ(std::stod(entries[0].first), 1e-7);
    EXPECT_EQ(std::stod(entries[1].first), awkward);
    EXPECT_EQ(std::stod(entries[2].first), 12345.678);
}


TEST_F(VtkSeries, restartDropsLaterTimesKeepsEarlierAndAppends)
{
    writeSeries({0, 0.5, 1});
    ASSERT_TRUE(fs::exists(dir/"case_000002.vtm"));

    seriesWriter restarted(dir.string(), "case", 0.25);

    // At once, before any write: only the first entry remains, on disk too
    EXPECT_EQ(restarted.entries().size(), 1u);
    EXPECT_EQ(restarted.nextIndex(), 1u);
    EXPECT_EQ
    (
        readCollection(pvd()),
        (collectionEntries{{"0", "case_000000.vtm"}})
    );
    EXPECT_TRUE(fs::exists(dir/"case_000000.vtm"));
    EXPECT_FALSE(fs::exists(dir/"case_000001.vtm"));
    EXPECT_FALSE(fs::exists(dir/"case_000001"));
    EXPECT_FALSE(fs::exists(dir/"case_000002.vtm"));
    EXPECT_FALSE(fs::exists(dir/"case_000002"));

    const meshFields fields(0.25);
    restarted.write(0.25, {fields.block()}, {});
    restarted.write(0.75, {fields.block()}, {});

    const collectionEntries expected =
    {
        {"0", "case_000000.vtm"},
        {"0.25", "case_000001.vtm"},
        {"0.75", "case_000002.vtm"}
    };
    EXPECT_EQ(readCollection(pvd()), expected);

    // The file now under index 1 holds the new time
    auto blocks = readMultiBlock(dir/"case_000001.vtm");
    ASSERT_TRUE(blocks);
    auto* grid = vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(0));
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->GetCellData()->GetArray("pressure")->GetComponent(0, 0),
              fields.pressure[0]);
}


TEST_F(VtkSeries, restartAtWrittenTimeDropsItDespiteRoundOff)
{
    // A run stepping 0.1 from 0 reaches 0.9999999999999999 after ten steps
    // and writes it; its restart reads the time directory "1"
    double time = 0;
    for (int step = 0; step < 10; ++step)
    {
        time += 0.1;
    }
    ASSERT_LT(time, 1.0) << "premise of the test";
    writeSeries({0, 0.5, time});

    seriesWriter restarted(dir.string(), "case", 1.0);
    EXPECT_EQ(restarted.entries().size(), 2u);
    EXPECT_EQ(restarted.nextIndex(), 2u);
    EXPECT_EQ(readCollection(pvd()).size(), 2u);
}


TEST_F(VtkSeries, restartAfterLastTimeKeepsEverything)
{
    writeSeries({0, 0.5});
    const auto before = fs::last_write_time(pvd());

    seriesWriter restarted(dir.string(), "case", 2);
    EXPECT_EQ(restarted.entries().size(), 2u);
    EXPECT_EQ(restarted.nextIndex(), 2u);
    EXPECT_EQ(fs::last_write_time(pvd()), before) << "collection rewritten";
}


TEST_F(VtkSeries, roundTripsEmptyAndSmallParticleBlocks)
{
    const std::vector<double> positions = {0.5, 0.25,  1.5, 0.75,  -1, 2};
    const std::vector<double> density = {1000, 1001.5, 999.25};
    const std::vector<double> velocity = {1, 2,  3, 4,  5, 6};

    {
        seriesWriter writer(dir.string(), "case", 0);
        const meshFields fields(0);
        writer.write
        (
            0,
            {fields.block()},
            {
                {"ghosts", 0, nullptr, {{"density", 1, nullptr}}},
                {
                    "particles", 3, positions.data(),
                    {{"density", 1, density.data()},
                     {"velocity", 2, velocity.data()}}
                }
            }
        );
    }

    auto blocks = readMultiBlock(dir/"case_000000.vtm");
    ASSERT_TRUE(blocks);
    ASSERT_EQ(blocks->GetNumberOfBlocks(), 3u);
    EXPECT_EQ(blockName(blocks, 0), "elements");
    EXPECT_EQ(blockName(blocks, 1), "ghosts");
    EXPECT_EQ(blockName(blocks, 2), "particles");

    // Empty block: present by name, as poly data without points or cells
    auto* ghosts = vtkPolyData::SafeDownCast(blocks->GetBlock(1));
    ASSERT_TRUE(ghosts) << "empty particle block missing or not poly data";
    EXPECT_EQ(ghosts->GetNumberOfPoints(), 0);
    EXPECT_EQ(ghosts->GetNumberOfCells(), 0);

    auto* particles = vtkPolyData::SafeDownCast(blocks->GetBlock(2));
    ASSERT_TRUE(particles) << "particle block is not poly data";
    ASSERT_EQ(particles->GetNumberOfPoints(), 3);
    ASSERT_EQ(particles->GetNumberOfVerts(), 3);
    ASSERT_EQ(particles->GetNumberOfCells(), 3);
    vtkNew<vtkIdList> nodes;
    for (vtkIdType i = 0; i < 3; ++i)
    {
        double x[3];
        particles->GetPoint(i, x);
        EXPECT_EQ(x[0], positions[2*i]);
        EXPECT_EQ(x[1], positions[2*i + 1]);
        EXPECT_EQ(x[2], 0.0);

        EXPECT_EQ(particles->GetCellType(i), VTK_VERTEX);
        particles->GetCellPoints(i, nodes);
        ASSERT_EQ(nodes->GetNumberOfIds(), 1);
        EXPECT_EQ(nodes->GetId(0), i);
    }

    vtkDataArray* rho = particles->GetPointData()->GetArray("density");
    ASSERT_TRUE(rho);
    ASSERT_EQ(rho->GetNumberOfComponents(), 1);
    vtkDataArray* u = particles->GetPointData()->GetArray("velocity");
    ASSERT_TRUE(u);
    ASSERT_EQ(u->GetNumberOfComponents(), 3);
    for (vtkIdType i = 0; i < 3; ++i)
    {
        EXPECT_EQ(rho->GetComponent(i, 0), density[i]);
        EXPECT_EQ(u->GetComponent(i, 0), velocity[2*i]);
        EXPECT_EQ(u->GetComponent(i, 1), velocity[2*i + 1]);
        EXPECT_EQ(u->GetComponent(i, 2), 0.0);
    }
}


TEST_F(VtkSeries, float32RoundsRealsAndKeepsIntegerFieldsExact)
{
    // precision::float32 (spemFoam's default vtkPrecision single): every
    // real array and the coordinates are Float32, each value the double
    // rounded to float; integer fields and the connectivity are Int32 and
    // exact, also beyond float's 2^24
    const meshFields fields(0.1 + 0.2);
    const std::vector<double> region = {0, 1, 2};
    const std::vector<double> positions = {1.0/3.0, 2.0/7.0,  -1e-3, 6e23};
    const std::vector<double> ids = {16777217, -5};   // 2^24 + 1
    const std::vector<double> rho = {1000.0/3.0, 999.1};
    const auto write = [&](const std::string& name, seriesWriter::precision p)
    {
        seriesWriter writer(dir.string(), name, 0, seriesWriter::format::raw, p);
        triangleBlock elements = fields.block();
        elements.cellData.push_back({"region", 1, region.data(), true});
        writer.write
        (
            0, {elements},
            {{
                "particles", 2, positions.data(),
                {{"density", 1, rho.data()}, {"id", 1, ids.data(), true}}
            }}
        );
        return dir/(name + "_000000");
    };
    const fs::path single = write("single", seriesWriter::precision::float32);
    const fs::path full = write("full", seriesWriter::precision::float64);

    auto blocks = readMultiBlock(single.string() + ".vtm");
    ASSERT_TRUE(blocks);
    auto* grid = vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(0));
    auto* cloud = vtkPolyData::SafeDownCast(blocks->GetBlock(1));
    ASSERT_TRUE(grid && cloud);

    EXPECT_EQ(grid->GetPoints()->GetDataType(), VTK_FLOAT);
    for (std::size_t p = 0; p < nMeshPoints; ++p)
    {
        double x[3];
        grid->GetPoint(vtkIdType(p), x);
        EXPECT_EQ(x[0], double(float(meshPoints[2*p])));
        EXPECT_EQ(x[1], double(float(meshPoints[2*p + 1])));
    }
    vtkNew<vtkIdList> nodes;
    for (std::size_t t = 0; t < nMeshTriangles; ++t)
    {
        grid->GetCellPoints(vtkIdType(t), nodes);
        ASSERT_EQ(nodes->GetNumberOfIds(), 3);
        for (int i = 0; i < 3; ++i)
        {
            EXPECT_EQ(nodes->GetId(i), meshTriangles[3*t + i]);
        }
    }
    vtkDataArray* stress = grid->GetCellData()->GetArray("stress");
    ASSERT_TRUE(stress);
    EXPECT_EQ(stress->GetDataType(), VTK_FLOAT);
    for (std::size_t t = 0; t < nMeshTriangles; ++t)
    {
        for (int c = 0; c < 6; ++c)
        {
            EXPECT_EQ
            (
                stress->GetComponent(t, c), double(float(fields.stress[6*t + c]))
            );
        }
    }
    vtkDataArray* regionArray = grid->GetCellData()->GetArray("region");
    ASSERT_TRUE(regionArray);
    EXPECT_EQ(regionArray->GetDataType(), VTK_INT);
    for (vtkIdType t = 0; t < 3; ++t)
    {
        EXPECT_EQ(regionArray->GetComponent(t, 0), region[t]);
    }

    EXPECT_EQ(cloud->GetPoints()->GetDataType(), VTK_FLOAT);
    vtkDataArray* id = cloud->GetPointData()->GetArray("id");
    vtkDataArray* density = cloud->GetPointData()->GetArray("density");
    ASSERT_TRUE(id && density);
    EXPECT_EQ(id->GetDataType(), VTK_INT);
    for (vtkIdType i = 0; i < 2; ++i)
    {
        double x[3];
        cloud->GetPoint(i, x);
        EXPECT_EQ(x[0], double(float(positions[2*i])));
        EXPECT_EQ(x[1], double(float(positions[2*i + 1])));
        EXPECT_EQ(id->GetComponent(i, 0), ids[i]);
        EXPECT_EQ(density->GetComponent(i, 0), double(float(rho[i])));
    }

    // Float64: the doubles as they are; the integers Int32 still
    blocks = readMultiBlock(full.string() + ".vtm");
    ASSERT_TRUE(blocks);
    grid = vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(0));
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->GetPoints()->GetDataType(), VTK_DOUBLE);
    EXPECT_EQ(grid->GetCellData()->GetArray("stress")->GetDataType(), VTK_DOUBLE);
    EXPECT_EQ(grid->GetCellData()->GetArray("region")->GetDataType(), VTK_INT);

    // A double beyond float's range is an infinity of its sign
    {
        const std::vector<double> huge = {1e300, -1e300, 3};
        triangleBlock big = fields.block();
        big.cellData.push_back({"huge", 1, huge.data()});
        seriesWriter(dir.string(), "huge", 0, seriesWriter::format::raw,
            seriesWriter::precision::float32).write(0, {big}, {});
        auto hugeBlocks = readMultiBlock(dir/"huge_000000.vtm");
        ASSERT_TRUE(hugeBlocks);
        auto* hugeGrid = vtkUnstructuredGrid::SafeDownCast(hugeBlocks->GetBlock(0));
        ASSERT_TRUE(hugeGrid);
        vtkDataArray* h = hugeGrid->GetCellData()->GetArray("huge");
        ASSERT_TRUE(h);
        EXPECT_EQ(h->GetComponent(0, 0), std::numeric_limits<double>::infinity());
        EXPECT_EQ(h->GetComponent(1, 0), -std::numeric_limits<double>::infinity());
        EXPECT_EQ(h->GetComponent(2, 0), 3.0);
    }

    // An integer field of more than one component is refused
    {
        const std::vector<double> pairs = {0, 1, 2, 3, 4, 5};
        triangleBlock bad = fields.block();
        bad.cellData.push_back({"pairs", 2, pairs.data(), true});
        seriesWriter writer(dir.string(), "pairs", 0);
        EXPECT_THROW(writer.write(0, {bad}, {}), std::invalid_argument);
    }

    // A value of an integer field that is not a whole number is refused
    const std::vector<double> notWhole = {0, 1.5, 2};
    triangleBlock bad = fields.block();
    bad.cellData.push_back({"region", 1, notWhole.data(), true});
    seriesWriter writer(dir.string(), "bad", 0);
    EXPECT_THROW(writer.write(0, {bad}, {}), std::invalid_argument);
}


TEST_F(VtkSeries, writesTimesWhereEveryBlockIsEmptyOrThereIsNone)
{
    // VTK's own multiblock writer writes no file at all in these cases
    {
        seriesWriter writer(dir.string(), "case", 0);
        writer.write(0, {}, {});
        writer.write
        (
            1,
            {{"elements", 0, nullptr, 0, nullptr, {}, {}}},
            {{"particles", 0, nullptr, {}}}
        );
    }

    EXPECT_EQ
    (
        readCollection(pvd()),
        (collectionEntries{{"0", "case_000000.vtm"}, {"1", "case_000001.vtm"}})
    );

    auto none = readMultiBlock(dir/"case_000000.vtm");
    ASSERT_TRUE(none);
    EXPECT_EQ(none->GetNumberOfBlocks(), 0u);

    auto empty = readMultiBlock(dir/"case_000001.vtm");
    ASSERT_TRUE(empty);
    ASSERT_EQ(empty->GetNumberOfBlocks(), 2u);
    EXPECT_EQ(blockName(empty, 0), "elements");
    EXPECT_EQ(blockName(empty, 1), "particles");
    auto* grid = vtkUnstructuredGrid::SafeDownCast(empty->GetBlock(0));
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->GetNumberOfPoints(), 0);
    EXPECT_EQ(grid->GetNumberOfCells(), 0);
    auto* cloud = vtkPolyData::SafeDownCast(empty->GetBlock(1));
    ASSERT_TRUE(cloud);
    EXPECT_EQ(cloud->GetNumberOfPoints(), 0);
}


TEST_F(VtkSeries, rejectsBadInputBeforeWritingAnything)
{
    seriesWriter writer(dir.string(), "case", 0);
    const meshFields fields(0);

    triangleBlock badComponents = fields.block();
    badComponents.cellData.push_back({"strain", 4, fields.stress.data()});
    EXPECT_THROW(writer.write(0, {badComponents}, {}), std::invalid_argument);

    const std::vector<int> badTriangles = {0, 1, 2,  0, 2, 5,  1, 4, 2};
    triangleBlock badLabel = fields.block();
    badLabel.triangles = badTriangles.data();
    EXPECT_THROW(writer.write(0, {badLabel}, {}), std::invalid_argument);

    triangleBlock twice = fields.block();
    twice.cellData.push_back({"pressure", 1, fields.pressure.data()});
    EXPECT_THROW(writer.write(0, {twice}, {}), std::invalid_argument);

    EXPECT_THROW(seriesWriter(dir.string(), "", 0), std::invalid_argument);

    EXPECT_FALSE(fs::exists(dir)) << "bad input reached the disk";
    EXPECT_EQ(writer.nextIndex(), 0u);
}


TEST_F(VtkSeries, restartFromUnreadableCollectionThrows)
{
    fs::create_directories(dir);
    std::ofstream(pvd()) << "<VTKFile type=\"Collection\"><Collection>";
    EXPECT_THROW(seriesWriter(dir.string(), "case", 0), std::runtime_error);
}


TEST_F(VtkSeries, opensInParaViewWhenPvpythonIsAvailable)
{
    if (std::system("command -v pvpython > /dev/null 2>&1") != 0)
    {
        GTEST_SKIP() << "pvpython not on PATH (Debian package paraview)";
    }

    const std::vector<double> positions = {0.5, 0.25,  1.5, 0.75};
    {
        seriesWriter writer(dir.string(), "case", 0);
        for (const double t : {0.0, 0.5})
        {
            const meshFields fields(t);
            writer.write
            (
                t,
                {fields.block()},
                {{"particles", 2, positions.data(), {}}}
            );
        }
    }

    const fs::path script = dir/"openSeries.py";
    std::ofstream(script)
        << "import sys\n"
        << "from paraview.simple import OpenDataFile, servermanager\n"
        << "reader = OpenDataFile(sys.argv[1])\n"
        << "reader.UpdatePipelineInformation()\n"
        << "times = list(reader.TimestepValues)\n"
        << "assert times == [0.0, 0.5], times\n"
        << "reader.UpdatePipeline(0.5)\n"
        << "data = servermanager.Fetch(reader)\n"
        << "n = data.GetNumberOfBlocks()\n"
        << "assert n == 2, n\n"
        << "names = [data.GetMetaData(i).Get(data.NAME()) for i in range(n)]\n"
        << "assert names == ['elements', 'particles'], names\n"
        << "assert data.GetBlock(0).GetNumberOfCells() == 3\n"
        << "print('pvpython opened the series')\n";

    const std::string command =
        "pvpython " + script.string() + " " + pvd().string();
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
}


// ************************************************************************* //
