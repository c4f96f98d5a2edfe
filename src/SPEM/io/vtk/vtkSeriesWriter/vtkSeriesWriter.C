#include "vtkSeriesWriter.H"

// VTK only: no OpenFOAM header may be included in this file (OpenFOAM's Log
// macro breaks vtkLogger.h), see vtkSeriesWriter.H
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkTypeInt32Array.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>

namespace fs = std::filesystem;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using namespace Foam::vtkOutput;

//- Component names ParaView uses for a 6-component symmetric tensor
const char* const symmTensorComponentNames[6] =
    {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};


//- Shortest text that reads back to the same double, locale independent
std::string timeName(const double time)
{
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), time);
    return std::string(buffer, result.ptr);
}


//- <baseName>_<zero-padded index>
std::string indexedName(const std::string& baseName, const std::size_t index)
{
    std::string digits = std::to_string(index);
    const std::size_t width = seriesWriter::indexWidth;
    if (digits.size() < width)
    {
        digits.insert(0, width - digits.size(), '0');
    }
    return baseName + '_' + digits;
}


//- Whether file is <baseName>_<digits>.vtm, i.e. written by a seriesWriter
//  of this baseName; its index if so
bool seriesIndex
(
    const std::string& file,
    const std::string& baseName,
    std::size_t& index
)
{
    const std::string prefix = baseName + '_';
    const std::string suffix = ".vtm";
    if
    (
        file.size() <= prefix.size() + suffix.size()
     || file.compare(0, prefix.size(), prefix) != 0
     || file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0
    )
    {
        return false;
    }
    const char* first = file.data() + prefix.size();
    const char* last = file.data() + file.size() - suffix.size();
    const auto result = std::from_chars(first, last, index);
    return result.ec == std::errc() && result.ptr == last;
}


//- Text with the five XML special characters escaped, for attribute values
std::string xmlEscape(const std::string& text)
{
    std::string escaped;
    escaped.reserve(text.size());
    for (const char c : text)
    {
        switch (c)
        {
            case '&': escaped += "&amp;"; break;
            case '<': escaped += "&lt;"; break;
            case '>': escaped += "&gt;"; break;
            case '"': escaped += "&quot;"; break;
            case '\'': escaped += "&apos;"; break;
            default: escaped += c;
        }
    }
    return escaped;
}


//- Entries of a collection file, in file order
std::vector<seriesWriter::entry> readCollection(const fs::path& file)
{
    const auto failure = [&file](const std::string& why)
    {
        return std::runtime_error
        (
            "vtkOutput::seriesWriter: cannot restart from collection file "
          + file.string() + ": " + why
          + " (remove or repair it to start a new series)"
        );
    };

    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(file.c_str());
    if (!parser->Parse())
    {
        throw failure("not valid XML");
    }

    vtkXMLDataElement* root = parser->GetRootElement();
    const char* type = root ? root->GetAttribute("type") : nullptr;
    if
    (
        !root
     || std::strcmp(root->GetName(), "VTKFile") != 0
     || !type
     || std::strcmp(type, "Collection") != 0
    )
    {
        throw failure("not a <VTKFile type=\"Collection\">");
    }
    vtkXMLDataElement* collection = root->FindNestedElementWithName
    (
        "Collection"
    );
    if (!collection)
    {
        throw failure("no <Collection> element");
    }

    std::vector<seriesWriter::entry> entries;
    const int n = collection->GetNumberOfNestedElements();
    for (int i = 0; i < n; ++i)
    {
        vtkXMLDataElement* dataSet = collection->GetNestedElement(i);
        if (std::strcmp(dataSet->GetName(), "DataSet") != 0)
        {
            continue;
        }
        const char* timestep = dataSet->GetAttribute("timestep");
        const char* fileName = dataSet->GetAttribute("file");
        if (!timestep || !fileName)
        {
            throw failure("<DataSet> without timestep or file");
        }
        seriesWriter::entry e{0, fileName};
        const char* last = timestep + std::strlen(timestep);
        const auto result = std::from_chars(timestep, last, e.time);
        if (result.ec != std::errc() || result.ptr != last)
        {
            throw failure("timestep \"" + std::string(timestep) + "\"");
        }
        entries.push_back(std::move(e));
    }
    return entries;
}


//- Check what the VTK conversion relies on; a bad label or component count
//  would otherwise give a file that crashes ParaView
void checkFields
(
    const std::vector<field>& fields,
    const std::size_t nTuples,
    const std::string& blockName
)
{
    std::set<std::string> names;
    for (const field& f : fields)
    {
        const std::string where =
            "vtkOutput::seriesWriter: field '" + f.name + "' of block '"
          + blockName + "'";
        if (f.name.empty())
        {
            throw std::invalid_argument
            (
                "vtkOutput::seriesWriter: field without name in block '"
              + blockName + "'"
            );
        }
        if (!names.insert(f.name).second)
        {
            // VTK would silently keep only the last array of a name
            throw std::invalid_argument(where + " appears twice");
        }
        if
        (
            f.nComponents != 1 && f.nComponents != 2
         && f.nComponents != 3 && f.nComponents != 6
        )
        {
            throw std::invalid_argument
            (
                where + " has " + std::to_string(f.nComponents)
              + " components; 1, 2, 3 or 6 expected"
            );
        }
        if (f.integer && f.nComponents != 1)
        {
            throw std::invalid_argument
            (
                where + " is an integer field of " + std::to_string(f.nComponents)
              + " components: integer fields have one"
            );
        }
        if (nTuples > 0 && !f.values)
        {
            throw std::invalid_argument(where + " has no values");
        }
    }
}


//- n tuples of nIn doubles (2: a 2D vector, stored with z = 0) into an
//  array of nStored components of the array's value type
template<class ArrayType>
void copyTuples
(
    ArrayType* array,
    const double* in,
    const int nIn,
    const int nStored,
    const std::size_t nTuples
)
{
    using valueType = typename ArrayType::ValueType;
    array->SetNumberOfComponents(nStored);
    array->SetNumberOfTuples(vtkIdType(nTuples));
    if (nTuples == 0) return;
    // A double beyond float's range becomes an infinity of its sign (the
    // plain conversion is undefined there); NaN stays NaN
    const auto stored = [](const double v)
    {
        if constexpr (std::is_same_v<valueType, float>)
        {
            constexpr double most = std::numeric_limits<float>::max();
            if (v > most) return std::numeric_limits<float>::infinity();
            if (v < -most) return -std::numeric_limits<float>::infinity();
        }
        return valueType(v);
    };
    // Performance-critical: plain loop over raw storage, no per-value
    // virtual calls (one write may hold millions of tuples)
    valueType* out = array->GetPointer(0);
    for (std::size_t i = 0; i < nTuples; ++i)
    {
        for (int c = 0; c < nIn; ++c)
        {
            out[nStored*i + c] = stored(in[nIn*i + c]);
        }
        for (int c = nIn; c < nStored; ++c) out[nStored*i + c] = 0;
    }
}


//- An integer field's values as Int32 (they are whole numbers in doubles)
void copyWholeNumbers
(
    vtkTypeInt32Array* array,
    const field& f,
    const std::size_t nTuples
)
{
    const std::size_t n = std::size_t(f.nComponents)*nTuples;
    array->SetNumberOfComponents(f.nComponents);
    array->SetNumberOfTuples(vtkIdType(nTuples));
    if (n == 0) return;
    vtkTypeInt32* out = array->GetPointer(0);
    bool whole = true;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double v = f.values[i];
        whole &= (v >= INT_MIN) & (v <= INT_MAX) & (v == std::trunc(v));
        out[i] = whole ? vtkTypeInt32(v) : 0;
    }
    if (!whole)
    {
        throw std::invalid_argument
        (
            "vtkOutput::seriesWriter: integer field '" + f.name
          + "' holds a value that is not a whole number of 32 bits"
        );
    }
}


//- A field as a VTK array: Int32 for an integer field; otherwise doubles
//  used in place (Float64, not a 2D vector) or copied (a 2D vector gets
//  z = 0; Float32 is rounded)
vtkSmartPointer<vtkDataArray> makeArray
(
    const field& f,
    const std::size_t nTuples,
    const seriesWriter::precision realPrecision
)
{
    const int nStored = f.nComponents == 2 ? 3 : f.nComponents;
    vtkSmartPointer<vtkDataArray> array;
    if (f.integer)
    {
        auto ints = vtkSmartPointer<vtkTypeInt32Array>::New();
        copyWholeNumbers(ints, f, nTuples);
        array = ints;
    }
    else if (realPrecision == seriesWriter::precision::float32)
    {
        auto floats = vtkSmartPointer<vtkFloatArray>::New();
        copyTuples(floats.Get(), f.values, f.nComponents, nStored, nTuples);
        array = floats;
    }
    else if (f.nComponents == 2 || nTuples == 0)
    {
        auto doubles = vtkSmartPointer<vtkDoubleArray>::New();
        copyTuples(doubles.Get(), f.values, f.nComponents, nStored, nTuples);
        array = doubles;
    }
    else
    {
        // No copy (it was a third of the conversion time at 1M triangles):
        // the array lives only inside write() and VTK's writers only read
        // it; SetArray wants a non-const pointer, save = 1 so that VTK
        // never frees the caller's memory
        auto doubles = vtkSmartPointer<vtkDoubleArray>::New();
        doubles->SetNumberOfComponents(nStored);
        doubles->SetArray
        (
            const_cast<double*>(f.values), vtkIdType(nStored*nTuples), 1
        );
        array = doubles;
    }
    array->SetName(f.name.c_str());
    if (f.nComponents == 6)
    {
        for (int c = 0; c < 6; ++c)
        {
            array->SetComponentName(c, symmTensorComponentNames[c]);
        }
    }
    return array;
}


//- 2D positions, (x, y) interleaved, as VTK points with z = 0
vtkSmartPointer<vtkPoints> makePoints
(
    const double* xy,
    const std::size_t n,
    const seriesWriter::precision realPrecision
)
{
    auto points = vtkSmartPointer<vtkPoints>::New();
    if (realPrecision == seriesWriter::precision::float32)
    {
        vtkNew<vtkFloatArray> xyz;
        copyTuples(xyz.Get(), xy, 2, 3, n);
        points->SetData(xyz);
    }
    else
    {
        vtkNew<vtkDoubleArray> xyz;
        copyTuples(xyz.Get(), xy, 2, 3, n);
        points->SetData(xyz);
    }
    return points;
}


//- Add the fields to point or cell data
void addFields
(
    vtkFieldData* data,
    const std::vector<field>& fields,
    const std::size_t nTuples,
    const seriesWriter::precision realPrecision
)
{
    for (const field& f : fields)
    {
        data->AddArray(makeArray(f, nTuples, realPrecision));
    }
}


//- The time as the "TimeValue" field-data array ParaView shows when a single
//  .vtm is opened without the collection
void addTimeValue(vtkDataSet* dataSet, const double time)
{
    vtkNew<vtkDoubleArray> timeValue;
    timeValue->SetName("TimeValue");
    timeValue->SetNumberOfTuples(1);
    timeValue->SetValue(0, time);
    dataSet->GetFieldData()->AddArray(timeValue);
}


//- A triangle block as an unstructured grid of VTK_TRIANGLE cells
vtkSmartPointer<vtkUnstructuredGrid> makeTriangleGrid
(
    const triangleBlock& block,
    const double time,
    const seriesWriter::precision realPrecision
)
{
    const std::string where =
        "vtkOutput::seriesWriter: triangle block '" + block.name + "'";
    if (block.nPoints > 0 && !block.points)
    {
        throw std::invalid_argument(where + " has no points");
    }
    if (block.nTriangles > 0 && !block.triangles)
    {
        throw std::invalid_argument(where + " has no triangles");
    }
    checkFields(block.pointData, block.nPoints, block.name);
    checkFields(block.cellData, block.nTriangles, block.name);

    // Performance-critical: copy and range-check in one branch-free pass
    const std::size_t nLabels = 3*block.nTriangles;
    // Int32: the labels are ints (half the bytes of VTK's default Int64);
    // the offsets, up to 3 nTriangles, must fit too
    if (block.nTriangles > std::size_t(INT_MAX)/3)
    {
        throw std::invalid_argument
        (
            where + " has more triangles than Int32 offsets can count"
        );
    }
    vtkNew<vtkTypeInt32Array> connectivity;
    connectivity->SetNumberOfValues(vtkIdType(nLabels));
    bool inRange = true;
    if (nLabels > 0)
    {
        vtkTypeInt32* out = connectivity->GetPointer(0);
        const vtkIdType nPoints = vtkIdType(block.nPoints);
        for (std::size_t i = 0; i < nLabels; ++i)
        {
            const vtkTypeInt32 label = block.triangles[i];
            inRange &= (label >= 0) & (label < nPoints);
            out[i] = label;
        }
    }
    if (!inRange)
    {
        const auto bad = std::find_if
        (
            block.triangles, block.triangles + nLabels,
            [&block](int label)
            {
                return label < 0 || std::size_t(label) >= block.nPoints;
            }
        );
        throw std::invalid_argument
        (
            where + ": triangle " + std::to_string((bad - block.triangles)/3)
          + " has node label " + std::to_string(*bad) + ", out of [0, "
          + std::to_string(block.nPoints) + ")"
        );
    }

    vtkNew<vtkCellArray> triangles;
    if (!triangles->SetData(3, connectivity))
    {
        throw std::runtime_error(where + ": VTK refused the connectivity");
    }

    auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
    grid->SetPoints(makePoints(block.points, block.nPoints, realPrecision));
    grid->SetCells(VTK_TRIANGLE, triangles);
    addFields
    (
        grid->GetPointData(), block.pointData, block.nPoints, realPrecision
    );
    addFields
    (
        grid->GetCellData(), block.cellData, block.nTriangles, realPrecision
    );
    addTimeValue(grid, time);
    return grid;
}


//- A particle block as poly data with one vertex cell per particle, so that
//  ParaView shows it in every representation, not only "Points"
vtkSmartPointer<vtkPolyData> makeParticleCloud
(
    const particleBlock& block,
    const double time,
    const seriesWriter::precision realPrecision
)
{
    if (block.nParticles > 0 && !block.positions)
    {
        throw std::invalid_argument
        (
            "vtkOutput::seriesWriter: particle block '" + block.name
          + "' has no positions"
        );
    }
    checkFields(block.pointData, block.nParticles, block.name);

    if (block.nParticles > std::size_t(INT_MAX))
    {
        throw std::invalid_argument
        (
            "vtkOutput::seriesWriter: particle block '" + block.name
          + "' has more particles than Int32 connectivity can label"
        );
    }
    vtkNew<vtkTypeInt32Array> connectivity;
    connectivity->SetNumberOfValues(vtkIdType(block.nParticles));
    if (block.nParticles > 0)
    {
        vtkTypeInt32* out = connectivity->GetPointer(0);
        for (std::size_t i = 0; i < block.nParticles; ++i)
        {
            out[i] = vtkTypeInt32(i);
        }
    }
    vtkNew<vtkCellArray> vertices;
    if (!vertices->SetData(1, connectivity))
    {
        throw std::runtime_error
        (
            "vtkOutput::seriesWriter: VTK refused the vertices of particle"
            " block '" + block.name + "'"
        );
    }

    auto cloud = vtkSmartPointer<vtkPolyData>::New();
    cloud->SetPoints
    (
        makePoints(block.positions, block.nParticles, realPrecision)
    );
    cloud->SetVerts(vertices);
    addFields
    (
        cloud->GetPointData(), block.pointData, block.nParticles,
        realPrecision
    );
    addTimeValue(cloud, time);
    return cloud;
}


//- Write a small text file aside and rename it over the old one (atomic on
//  POSIX), so that ParaView or a crash never sees it half-written
void writeAtomically(const fs::path& file, const std::string& text)
{
    fs::path temporary = file;
    temporary += ".tmp";
    {
        std::ofstream os(temporary, std::ios::out | std::ios::trunc);
        os << text;
        os.close();
        if (!os)
        {
            throw std::runtime_error
            (
                "vtkOutput::seriesWriter: cannot write " + temporary.string()
            );
        }
    }

    std::error_code ec;
    fs::rename(temporary, file, ec);
    if (ec)
    {
        throw std::runtime_error
        (
            "vtkOutput::seriesWriter: cannot rename " + temporary.string()
          + " to " + file.string() + ": " + ec.message()
        );
    }
}


//- Write one block with VTK's XML writer for its type: binary appended
//  (raw, not base64), compressed as chosen, or ascii
void writePiece
(
    vtkDataSet* dataSet,
    const fs::path& file,
    const seriesWriter::format dataFormat
)
{
    vtkSmartPointer<vtkXMLWriter> writer;
    if (vtkUnstructuredGrid::SafeDownCast(dataSet))
    {
        writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
    }
    else
    {
        writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    }
    writer->SetFileName(file.c_str());
    writer->SetInputData(dataSet);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    switch (dataFormat)
    {
        case seriesWriter::format::raw:
            writer->SetCompressorTypeToNone();
            break;
        case seriesWriter::format::lz4:
            writer->SetCompressorTypeToLZ4();
            break;
        case seriesWriter::format::zlib:
            writer->SetCompressorTypeToZLib();
            writer->SetCompressionLevel(seriesWriter::zlibLevel);
            break;
        case seriesWriter::format::ascii:
            writer->SetDataModeToAscii();
            writer->SetCompressorTypeToNone();
            break;
    }

    // A failed VTK pipeline does not always set the error code: check that
    // the file is there as well
    std::error_code ec;
    if
    (
        writer->Write() != 1
     || writer->GetErrorCode() != vtkErrorCode::NoError
     || !fs::exists(file, ec)
    )
    {
        throw std::runtime_error
        (
            "vtkOutput::seriesWriter: cannot write " + file.string() + ": "
          + vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode())
        );
    }
}


//- The multiblock index of one time, as vtkXMLMultiBlockDataWriter writes
//  it but listing empty blocks too (that writer drops them, VTK bug 15942),
//  so that every block keeps its name and place at every time
std::string multiBlockIndex
(
    const std::vector<std::string>& blockNames,
    const std::vector<std::string>& blockFiles
)
{
    std::ostringstream os;
    os  << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n"
        << "  <vtkMultiBlockDataSet>\n";
    for (std::size_t i = 0; i < blockNames.size(); ++i)
    {
        os  << "    <DataSet index=\"" << i
            << "\" name=\"" << xmlEscape(blockNames[i])
            << "\" file=\"" << xmlEscape(blockFiles[i]) << "\"/>\n";
    }
    os  << "  </vtkMultiBlockDataSet>\n"
        << "</VTKFile>\n";
    return os.str();
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::vtkOutput::seriesWriter::writeCollection() const
{
    std::ostringstream os;
    os  << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\">\n"
        << "  <Collection>\n";
    for (const entry& e : entries_)
    {
        os  << "    <DataSet timestep=\"" << timeName(e.time)
            << "\" file=\"" << xmlEscape(e.file) << "\"/>\n";
    }
    os  << "  </Collection>\n"
        << "</VTKFile>\n";
    writeAtomically(collectionFile(), os.str());
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::vtkOutput::seriesWriter::seriesWriter
(
    const std::string& dir,
    const std::string& baseName,
    const double startTime,
    const format dataFormat,
    const precision realPrecision
)
:
    dir_(dir),
    baseName_(baseName),
    format_(dataFormat),
    precision_(realPrecision),
    entries_(),
    nextIndex_(0)
{
    if (baseName_.empty() || baseName_.find('/') != std::string::npos)
    {
        throw std::invalid_argument
        (
            "vtkOutput::seriesWriter: base name '" + baseName_
          + "' must be a non-empty file name without '/'"
        );
    }

    const fs::path file = collectionFile();
    std::error_code ec;
    if (!fs::exists(file, ec))
    {
        return;
    }

    const double tolerance = restartTimeTolerance*std::abs(startTime);
    std::vector<entry> dropped;
    for (entry& e : readCollection(file))
    {
        if (e.time >= startTime - tolerance)
        {
            dropped.push_back(std::move(e));
        }
        else
        {
            entries_.push_back(std::move(e));
        }
    }

    // Continue after the kept entries, and never onto a kept file
    nextIndex_ = entries_.size();
    for (const entry& e : entries_)
    {
        std::size_t index = 0;
        if (seriesIndex(e.file, baseName_, index))
        {
            nextIndex_ = std::max(nextIndex_, index + 1);
        }
    }

    if (!dropped.empty())
    {
        writeCollection();

        // Only files of our own naming: the collection is not trusted to
        // point at nothing else
        for (const entry& e : dropped)
        {
            std::size_t index = 0;
            if (seriesIndex(e.file, baseName_, index))
            {
                const fs::path vtm = fs::path(dir_)/e.file;
                fs::remove(vtm, ec);
                fs::remove_all(fs::path(dir_)/vtm.stem(), ec);
            }
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

std::string Foam::vtkOutput::seriesWriter::collectionFile() const
{
    return (fs::path(dir_)/(baseName_ + ".pvd")).string();
}


void Foam::vtkOutput::seriesWriter::write
(
    const double time,
    const std::vector<triangleBlock>& triangleBlocks,
    const std::vector<particleBlock>& particleBlocks
)
{
    // Convert everything first: bad input throws before the disk is touched
    std::vector<vtkSmartPointer<vtkDataSet>> blocks;
    std::vector<std::string> blockNames;
    for (const triangleBlock& block : triangleBlocks)
    {
        blocks.push_back(makeTriangleGrid(block, time, precision_));
        blockNames.push_back(block.name);
    }
    for (const particleBlock& block : particleBlocks)
    {
        blocks.push_back(makeParticleCloud(block, time, precision_));
        blockNames.push_back(block.name);
    }

    // Pieces in <stem>/, named as vtkXMLMultiBlockDataWriter names them
    const std::string stem = indexedName(baseName_, nextIndex_);
    const fs::path pieceDir = fs::path(dir_)/stem;
    std::error_code ec;
    // Pieces left by an earlier run under this index would linger otherwise
    fs::remove_all(pieceDir, ec);
    fs::create_directories(pieceDir, ec);
    if (ec)
    {
        throw std::runtime_error
        (
            "vtkOutput::seriesWriter: cannot create " + pieceDir.string()
          + ": " + ec.message()
        );
    }

    std::vector<std::string> blockFiles;
    for (std::size_t i = 0; i < blocks.size(); ++i)
    {
        const bool isGrid = i < triangleBlocks.size();
        blockFiles.push_back
        (
            stem + '/' + stem + '_' + std::to_string(i)
          + (isGrid ? ".vtu" : ".vtp")
        );
        writePiece
        (
            blocks[i], fs::path(dir_)/blockFiles.back(), format_
        );
    }

    // Index after its pieces, collection after the index: neither ever
    // lists a file that is not complete
    writeAtomically
    (
        fs::path(dir_)/(stem + ".vtm"),
        multiBlockIndex(blockNames, blockFiles)
    );
    entries_.push_back({time, stem + ".vtm"});
    ++nextIndex_;
    writeCollection();
}


// ************************************************************************* //
