// SPDX-License-Identifier: BSD-3-Clause
// The bad-input catalogue: every entry point (models, expressions, molecule files,
// algorithm settings) fed inputs users will type. Each case must report an error whose
// text names the problem, leave an empty output without NaN coordinates, and return
// within its time budget; never crash or hang.
#include "PiTestUtilities.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiMoleculeReader.h"
#include "vtkPiMoleculeSurface.h"
#include "vtkPiPrimitive.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSampleFunction.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceModelReader.h"
#include "vtkPiSurfaceSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtksys/SystemTools.hxx"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

// Collects everything VTK prints (errors of inner objects and of the executive too), so
// a case can assert on the text and the test log stays readable.
class CaptureWindow : public vtkOutputWindow
{
public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);
  void DisplayText(const char* t) override { this->Text += t ? t : ""; }
  void DisplayErrorText(const char* t) override { this->Text += t ? t : ""; }
  void DisplayWarningText(const char* t) override { this->Text += t ? t : ""; }
  void DisplayGenericWarningText(const char* t) override { this->Text += t ? t : ""; }
  void DisplayDebugText(const char* t) override { this->Text += t ? t : ""; }
  std::string Text;
};
vtkStandardNewMacro(CaptureWindow);

using Output = vtkSmartPointer<vtkDataObject>;

struct Case
{
  std::string Name;
  std::string Expected;        // a substring of the error text
  std::function<Output()> Run; // returns the output to inspect (may be null)
  double Seconds = 60;         // budget: beyond it the case counts as a hang
};

std::string TempDir()
{
  const std::string dir = std::string(PISURF_TEMP_DIR) + "/BadInput";
  vtksys::SystemTools::MakeDirectory(dir);
  return dir;
}

std::string WriteFile(const std::string& name, const std::string& content)
{
  const std::string path = TempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

// A model with one sphere and `extra` inserted into the sphere's object.
std::string Sphere(const std::string& extra)
{
  return "{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": \"sphere\", "
         "\"radius\": 1" +
    extra + "}]}";
}

// A polynomial model in the unit box.
std::string Polynomial(const std::string& expression, const std::string& parameters = "")
{
  std::string escaped;
  for (char c : expression)
  {
    if (c == '"' || c == '\\')
    {
      escaped += '\\';
    }
    escaped += c;
  }
  return "{\"pisurf\": 1, \"blending\": 0, \"bounds\": [-1, 1, -1, 1, -1, 1], " +
    (parameters.empty() ? std::string() : "\"parameters\": " + parameters + ", ") +
    "\"primitives\": [{\"type\": \"polynomial\", \"expression\": \"" + escaped + "\"}]}";
}

Output Source(const std::string& model, const std::function<void(vtkPiSurfaceSource*)>& set = {})
{
  vtkNew<vtkPiSurfaceSource> source;
  source->SetModel(model.c_str());
  source->SetResolution(24);
  if (set)
  {
    set(source);
  }
  source->Update();
  return source->GetOutput();
}

// The mesher on a primitive built through the VTK API (not JSON).
Output PrimitiveMesher(const std::function<void(vtkPiPrimitive*)>& set)
{
  vtkNew<vtkPiPrimitive> p;
  set(p);
  vtkNew<vtkPiSurface> surface;
  surface->AddFactor(p);
  surface->SetModelBounds(std::vector<double>{ -1, 1, -1, 1, -1, 1 }.data());
  vtkNew<vtkPiFlyingEdges> mesher;
  mesher->SetPiSurface(surface);
  mesher->SetResolution(16);
  mesher->Update();
  return mesher->GetOutput();
}

Output Expression(const std::string& expression)
{
  return PrimitiveMesher(
    [&](vtkPiPrimitive* p)
    {
      p->SetTypeToPolynomial();
      p->SetExpression(expression.c_str());
    });
}

Output ModelReader(const std::string& path)
{
  vtkNew<vtkPiSurfaceModelReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetResolution(24);
  reader->Update();
  return reader->GetOutput();
}

Output MoleculeReader(const std::string& path, int model = 1, bool waters = false)
{
  vtkNew<vtkPiMoleculeReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetModel(model);
  reader->SetIncludeWaters(waters);
  reader->Update();
  return reader->GetOutput();
}

// A PDB ATOM record with the columns where the format puts them.
std::string Atom(int serial, const char* name, const char* residue, int seq, double x, double y,
  double z, const char* element, const char* record = "ATOM  ")
{
  char line[96];
  std::snprintf(line, sizeof(line),
    "%-6s%5d %-4s %3s A%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2s\n", record, serial % 100000,
    name, residue, seq % 10000, x, y, z, element);
  return line;
}

std::string SmallPdb()
{
  return Atom(1, " N  ", "ALA", 1, 0, 0, 0, " N") + Atom(2, " CA ", "ALA", 1, 1.46, 0, 0, " C") +
    Atom(3, " C  ", "ALA", 1, 2.0, 1.4, 0, " C") + Atom(4, " O  ", "ALA", 1, 1.3, 2.4, 0, " O") +
    "END\n";
}

vtkSmartPointer<vtkMolecule> Molecule(const std::vector<std::vector<double>>& atoms)
{
  auto m = vtkSmartPointer<vtkMolecule>::New();
  for (const auto& a : atoms)
  {
    m->AppendAtom(static_cast<unsigned short>(a[0]), a[1], a[2], a[3]);
  }
  return m;
}

Output MoleculeSurface(
  vtkDataObject* input, const std::function<void(vtkPiMoleculeSurface*)>& set = {})
{
  vtkNew<vtkPiMoleculeSurface> surface;
  surface->SetInputData(input);
  if (set)
  {
    set(surface);
  }
  surface->Update();
  return surface->GetOutput();
}

const std::vector<std::vector<double>> Water = { { 8, 0, 0, 0 }, { 1, 0.96, 0, 0 },
  { 1, -0.24, 0.93, 0 } };

// The ray caster on the default two spheres (or a camera).
Output RayCaster(const std::function<void(vtkPiRayCaster*)>& set)
{
  vtkNew<vtkPiSurface> surface;
  surface->SetModelJSON("{\"pisurf\": 1, \"blending\": 0.25, \"primitives\": [{\"type\": "
                        "\"sphere\", \"radius\": 1}]}");
  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(surface);
  caster->SetResolution(16, 16);
  set(caster);
  caster->Update();
  // The image port must be empty as well.
  if (caster->GetOutputDataObject(1) &&
    vtkImageData::SafeDownCast(caster->GetOutputDataObject(1))->GetNumberOfPoints() > 0)
  {
    return caster->GetOutputDataObject(1);
  }
  return caster->GetOutput();
}

// The grid sampler on the one-sphere model (or none).
Output Sampler(const std::function<void(vtkPiSampleFunction*)>& set, bool withSurface = true)
{
  vtkNew<vtkPiSurface> surface;
  surface->SetModelJSON("{\"pisurf\": 1, \"blending\": 0.25, \"primitives\": [{\"type\": "
                        "\"sphere\", \"radius\": 1}]}");
  vtkNew<vtkPiSampleFunction> sampler;
  if (withSurface)
  {
    sampler->SetPiSurface(surface);
  }
  sampler->SetSampleDimensions(8, 8, 8);
  set(sampler);
  sampler->Update();
  return sampler->GetOutput();
}

// Hits of a valid ray cast, then edited to be bad, into the triangulator.
Output Triangulator(const std::function<void(vtkPolyData*)>& spoil, int mode = 0)
{
  vtkNew<vtkPiSurface> surface;
  surface->SetModelJSON("{\"pisurf\": 1, \"blending\": 0.25, \"primitives\": [{\"type\": "
                        "\"sphere\", \"radius\": 1}]}");
  vtkNew<vtkPiRayCaster> caster;
  caster->SetPiSurface(surface);
  caster->SetResolution(12, 12);
  caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
  caster->Update();
  vtkNew<vtkPolyData> hits;
  hits->DeepCopy(caster->GetOutput());
  spoil(hits);
  vtkNew<vtkPiImageTriangulator> triangulator;
  triangulator->SetInputData(hits);
  triangulator->SetMergeMode(mode);
  triangulator->Update();
  return triangulator->GetOutput();
}

// Empty (no points, no cells) and no NaN coordinates.
bool Empty(vtkDataObject* o, std::string& why)
{
  if (!o)
  {
    return true;
  }
  if (auto* m = vtkMolecule::SafeDownCast(o))
  {
    if (m->GetNumberOfAtoms() > 0)
    {
      why = std::to_string(m->GetNumberOfAtoms()) + " atoms in the output";
      return false;
    }
    return true;
  }
  if (auto* ps = vtkPointSet::SafeDownCast(o))
  {
    if (ps->GetPoints())
    {
      for (vtkIdType i = 0; i < ps->GetNumberOfPoints(); ++i)
      {
        double p[3];
        ps->GetPoint(i, p);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        {
          why = "a non-finite coordinate in the output";
          return false;
        }
      }
    }
    if (ps->GetNumberOfPoints() > 0 || ps->GetNumberOfCells() > 0)
    {
      why = std::to_string(ps->GetNumberOfPoints()) + " points in the output";
      return false;
    }
    return true;
  }
  if (auto* ds = vtkDataSet::SafeDownCast(o))
  {
    if (ds->GetNumberOfPoints() > 0)
    {
      why = std::to_string(ds->GetNumberOfPoints()) + " points in the output image";
      return false;
    }
  }
  return true;
}

std::vector<Case> Catalogue()
{
  std::vector<Case> c;
  auto add = [&](const std::string& name, const std::string& expected, std::function<Output()> run,
               double seconds = 60) {
    c.push_back({ name, expected, std::move(run), seconds });
  };

  // ---- .pisurf models: syntax, schema, types, ranges, non-finite numbers, sizes.
  add("model.syntax.unterminated", "invalid JSON at line 1",
    [] { return Source("{\"pisurf\": 1, \"blending\": 0.25,"); });
  add("model.syntax.trailing_garbage", "invalid JSON",
    [] { return Source(Sphere("") + " trailing"); });
  add("model.syntax.empty_text", "invalid JSON", [] { return Source(""); });
  add(
    "model.syntax.nan_literal", "invalid JSON", [] { return Source(Sphere(", \"scale\": NaN")); });
  add("model.syntax.line_column", "line 3, column",
    [] { return Source("{\n\"pisurf\": 1,\n\"blending\": 0.1 \"primitives\": []}"); });
  add("model.schema.top_level_array", "the top level must be a JSON object",
    [] { return Source("[1, 2, 3]"); });
  add("model.schema.no_version", "missing key 'pisurf'",
    [] { return Source("{\"blending\": 0.1, \"primitives\": []}"); });
  add("model.schema.version_2", "unsupported version",
    [] {
      return Source("{\"pisurf\": 2, \"blending\": 0.1, \"primitives\": [{\"type\": \"sphere\"}]}");
    });
  add("model.schema.unknown_top_key", "unknown key 'colour'",
    [] { return Source("{\"pisurf\": 1, \"colour\": 1, \"blending\": 0.1, \"primitives\": []}"); });
  add("model.schema.no_primitives", "a model needs at least one primitive",
    [] { return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": []}"); });
  add("model.schema.unknown_type", "unknown primitive type 'blob'",
    [] {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": \"blob\"}]}");
    });
  add("model.schema.key_of_other_type", "unknown key 'major_radius'",
    [] { return Source(Sphere(", \"major_radius\": 2")); });
  add("model.schema.axis_and_rotation", "either 'axis' or 'rotation'",
    [] {
      return Source(Sphere(", \"axis\": [0,0,1], \"rotation\": {\"axis\": [0,0,1], \"angle\": 3}"));
    });
  add("model.schema.unbounded_without_bounds", "bounds: required",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": \"plane\", "
                    "\"normal\": [0, 0, 1]}]}");
    });
  add("model.type.blending_string", "blending: expected a number, got string",
    [] { return Source("{\"pisurf\": 1, \"blending\": \"0.1\", \"primitives\": []}"); });
  add("model.type.center_two_numbers", "primitives[0].center: expected an array of 3 numbers",
    [] { return Source(Sphere(", \"center\": [1, 2]")); });
  add("model.type.negate_number", "primitives[0].negate: expected true or false",
    [] { return Source(Sphere(", \"negate\": 1")); });
  add("model.type.primitive_not_object", "primitives[0]: expected an object",
    [] { return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [3]}"); });
  add("model.range.negative_radius", "primitives[0]",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": \"sphere\", "
                    "\"radius\": -1}]}");
    });
  add("model.range.zero_radius", "radius",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": \"sphere\", "
                    "\"radius\": 0}]}");
    });
  add("model.range.odd_exponent", "must be an even integer",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [{\"type\": "
                    "\"superellipsoid\", \"radii\": [1, 1, 1], \"exponent\": 3}]}");
    });
  add("model.range.cone_angle_90", "angle",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"bounds\": [-1,1,-1,1,-1,1], "
                    "\"primitives\": [{\"type\": \"cone\", \"angle\": 90}]}");
    });
  add("model.range.zero_normal", "normal",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"bounds\": [-1,1,-1,1,-1,1], "
                    "\"primitives\": [{\"type\": \"plane\", \"normal\": [0, 0, 0]}]}");
    });
  add("model.range.zero_scale", "scale", [] { return Source(Sphere(", \"scale\": 0")); });
  add("model.range.inverted_bounds", "bounds: expected [x0, x1, y0, y1, z0, z1]",
    []
    {
      return Source("{\"pisurf\": 1, \"blending\": 0.1, \"bounds\": [1, -1, -1, 1, -1, 1], "
                    "\"primitives\": [{\"type\": \"sphere\", \"radius\": 1}]}");
    });
  add("model.range.bad_parameter_name", "invalid parameter name",
    [] { return Source(Polynomial("x", "{\"x\": 1}")); });
  add("model.nonfinite.overflowing_number", "numbers must be finite",
    [] { return Source(Sphere(", \"center\": [1e999, 0, 0]")); });
  add("model.nonfinite.infinity_literal", "invalid JSON",
    [] { return Source(Sphere(", \"scale\": -Infinity")); });
  add("model.size.huge_array", "primitives[0].center: expected an array of 3 numbers",
    []
    {
      std::string big = "[0";
      for (int i = 0; i < 1000000; ++i)
      {
        big += ",0";
      }
      return Source(Sphere(", \"center\": " + big + "]"));
    });
  add("model.size.deep_nesting", "JSON nested deeper than 32 levels",
    [] { return Source(std::string(100000, '[') + std::string(100000, ']')); });
  add(
    "model.size.million_primitives", "more than 100000 primitives",
    []
    {
      std::string model = "{\"pisurf\": 1, \"blending\": 0.1, \"primitives\": [";
      model.reserve(40u << 20);
      for (int i = 0; i < 1000000; ++i)
      {
        model += i ? ",{\"type\":\"sphere\",\"radius\":1}" : "{\"type\":\"sphere\",\"radius\":1}";
      }
      return Source(model + "]}");
    },
    120);
  add("model.reader.missing_file", "cannot open model file",
    [] { return ModelReader(TempDir() + "/no_such_file.pisurf"); });
  add("model.reader.directory", "is a directory", [] { return ModelReader(TempDir()); });
  add("model.reader.empty_file", "invalid JSON",
    [] { return ModelReader(WriteFile("empty.pisurf", "")); });
  add("model.reader.binary_garbage", "invalid JSON",
    []
    {
      std::string garbage;
      for (int i = 0; i < 4096; ++i)
      {
        garbage += static_cast<char>((i * 7919 + 13) % 256);
      }
      return ModelReader(WriteFile("garbage.pisurf", garbage));
    });
  add("model.reader.no_file_name", "No FileName",
    []
    {
      vtkNew<vtkPiSurfaceModelReader> reader;
      reader->Update();
      return Output(reader->GetOutput());
    });

  // ---- Expressions, in a model and through vtkPiPrimitive.
  const char* const expressionErrors[][2] = {
    { "x^2 +", "unexpected end of expression at position" },
    { "x ** 2", "unexpected '*' (write '^' for a power" },
    { "(x + 1", "missing ')'" },
    { "x + 1)", "unexpected ')'" },
    { "2 x", "write '*' for multiplication" },
    { "x^2.5", "exponent must be a non-negative integer" },
    { "x^-1", "exponent must be a non-negative integer" },
    { "x^y", "exponent must be a constant" },
    { "10^400", "coefficient overflow" },
    { "2^2^2^2^2*x", "coefficient overflow" },
    { "x^100000", "degree above" },
    { "(x+y+z)^40 * (x+y+z)^40", "degree above" },
    { "x/0", "division by zero" },
    { "x/(2-2)", "division by zero" },
    { "x/y", "division by a non-constant" },
    { "a*x", "unknown name 'a'" },
    { "sin(x)", "unknown name 'sin'" },
    { "1e999*x", "number out of range" },
    { "1e*x", "malformed number (exponent digits missing)" },
    { "x $ y", "unexpected '$'" },
    { "   ", "empty expression" },
  };
  for (const auto& e : expressionErrors)
  {
    const std::string text = e[0], expected = e[1];
    add("expression.model." + text, expected, [text] { return Source(Polynomial(text)); });
  }
  add("expression.model.deep_parentheses", "nesting deeper than 200",
    [] { return Source(Polynomial(std::string(5000, '(') + "x" + std::string(5000, ')'))); });
  add("expression.model.deep_unary_minus", "nesting deeper than 200",
    [] { return Source(Polynomial(std::string(100000, '-') + "x")); });
  add("expression.model.nonfinite_parameter", "numbers must be finite",
    [] { return Source(Polynomial("a*x", "{\"a\": 1e400}")); });
  add("expression.primitive.syntax", "unexpected end of expression",
    [] { return Expression("x^2 + y^2 -"); });
  add("expression.primitive.unknown_name", "unknown name 'r'",
    [] { return Expression("x^2 + y^2 + z^2 - r"); });
  add("expression.primitive.nan_parameter", "must be a finite number",
    []
    {
      return PrimitiveMesher(
        [](vtkPiPrimitive* p)
        {
          p->SetTypeToPolynomial();
          p->SetParameter("r", NaN);
          p->SetExpression("x^2 + y^2 + z^2 - r");
        });
    });

  // ---- Primitives and the surface through the VTK API.
  add("primitive.nan_radius", "radius",
    [] { return PrimitiveMesher([](vtkPiPrimitive* p) { p->SetRadius(NaN); }); });
  add("primitive.negative_minor_radius", "minor",
    []
    {
      return PrimitiveMesher(
        [](vtkPiPrimitive* p)
        {
          p->SetTypeToTorus();
          p->SetMinorRadius(-0.2);
        });
    });
  add("primitive.odd_exponent", "exponent",
    []
    {
      return PrimitiveMesher(
        [](vtkPiPrimitive* p)
        {
          p->SetTypeToSuperellipsoid();
          p->SetExponent(5);
        });
    });
  add("surface.nan_blending", "Blending must be a finite number",
    []
    {
      return Source(Sphere(""),
        [](vtkPiSurfaceSource* s)
        {
          s->SetOverrideBlending(true);
          s->SetBlending(NaN);
        });
    });
  add("surface.no_factors", "has no factors",
    []
    {
      vtkNew<vtkPiSurface> surface;
      vtkNew<vtkPiFlyingEdges> mesher;
      mesher->SetPiSurface(surface);
      mesher->Update();
      return Output(mesher->GetOutput());
    });

  // ---- Mesher settings.
  add("mesher.resolution_zero", "Resolution must be at least 1",
    [] { return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetResolution(0); }); });
  add("mesher.resolution_negative", "Resolution must be at least 1",
    [] { return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetResolution(-7); }); });
  add("mesher.resolution_huge", "MiB; the limit is 2048 MiB",
    [] { return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetResolution(100000); }); });
  add("mesher.resolution_int_max", "MiB; the limit is 2048 MiB",
    []
    { return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetResolution(VTK_INT_MAX); }); });
  add("mesher.sample_dimensions_one", "SampleDimensions must be at least 2",
    []
    { return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetSampleDimensions(1, 1, 1); }); });
  add("mesher.sample_dimensions_huge", "MiB; the limit is",
    []
    {
      return Source(Sphere(""),
        [](vtkPiSurfaceSource* s) { s->SetSampleDimensions(VTK_INT_MAX, VTK_INT_MAX, 2); });
    });
  add("mesher.inverted_bounds", "x0 < x1",
    [] {
      return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetBounds(1, -1, -1, 1, -1, 1); });
    });
  add("mesher.flat_bounds", "x0 < x1",
    [] {
      return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetBounds(-1, 1, 0, 0, -1, 1); });
    });
  add("mesher.nan_bounds", "bounds must be finite",
    [] {
      return Source(Sphere(""), [](vtkPiSurfaceSource* s) { s->SetBounds(NaN, 1, -1, 1, -1, 1); });
    });
  add("mesher.infinite_bounds", "bounds must be finite",
    []
    {
      return Source(
        Sphere(""), [](vtkPiSurfaceSource* s) { s->SetBounds(-Inf, Inf, -1, 1, -1, 1); });
    });
  add("mesher.huge_bounds", "bounds must be finite",
    []
    {
      // Finite, but the side overflows: the spacing would be infinite.
      return Source(
        Sphere(""), [](vtkPiSurfaceSource* s) { s->SetBounds(-1e308, 1e308, -1, 1, -1, 1); });
    });
  add("mesher.ray_cast_method_resolution_zero", "Resolution must be at least 1",
    []
    {
      return Source(Sphere(""),
        [](vtkPiSurfaceSource* s)
        {
          s->SetMethod(vtkPiSurfaceSource::RAY_CAST_TRIANGULATION);
          s->SetResolution(0);
        });
    });
  add("mesher.ray_cast_method_resolution_huge", "MiB; the limit is",
    []
    {
      return Source(Sphere(""),
        [](vtkPiSurfaceSource* s)
        {
          s->SetMethod(vtkPiSurfaceSource::RAY_CAST_TRIANGULATION);
          s->SetResolution(20000);
        });
    });

  // ---- Ray caster settings.
  add("raycaster.resolution_zero", "Resolution must be at least 1 x 1",
    [] { return RayCaster([](vtkPiRayCaster* r) { r->SetResolution(0, 16); }); });
  add("raycaster.resolution_negative", "Resolution must be at least 1 x 1",
    [] { return RayCaster([](vtkPiRayCaster* r) { r->SetResolution(16, -3); }); });
  add("raycaster.resolution_huge", "the limit is 2048 MiB",
    []
    { return RayCaster([](vtkPiRayCaster* r) { r->SetResolution(VTK_INT_MAX, VTK_INT_MAX); }); });
  add("sampler.no_surface", "No Pi-surface",
    [] { return Sampler([](vtkPiSampleFunction*) {}, false); });
  add("sampler.dimensions_one", "at least 2 points per axis",
    [] { return Sampler([](vtkPiSampleFunction* f) { f->SetSampleDimensions(1, 8, 8); }); });
  add("sampler.dimensions_negative", "at least 2 points per axis",
    [] { return Sampler([](vtkPiSampleFunction* f) { f->SetSampleDimensions(8, -4, 8); }); });
  add("sampler.dimensions_huge", "the limit is 2048 MiB",
    []
    {
      return Sampler(
        [](vtkPiSampleFunction* f) { f->SetSampleDimensions(100000, 100000, 100000); });
    });
  add("sampler.inverted_bounds", "x0 < x1",
    [] { return Sampler([](vtkPiSampleFunction* f) { f->SetModelBounds(1, -1, -1, 1, -1, 1); }); });
  add("sampler.nan_bounds", "finite",
    []
    {
      return Sampler(
        [](vtkPiSampleFunction* f) { f->SetModelBounds(std::nan(""), 1, -1, 1, -1, 1); });
    });
  add("raycaster.inverted_bounds", "x0 < x1",
    [] { return RayCaster([](vtkPiRayCaster* r) { r->SetBounds(1, -1, -1, 1, -1, 1); }); });
  add("raycaster.camera_at_focal_point", "CameraPosition equals CameraFocalPoint",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraPosition(1, 2, 3);
          r->SetCameraFocalPoint(1, 2, 3);
        });
    });
  add("raycaster.view_up_parallel", "CameraViewUp is parallel",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraPosition(0, 0, 5);
          r->SetCameraFocalPoint(0, 0, 0);
          r->SetCameraViewUp(0, 0, 1);
        });
    });
  add("raycaster.nan_camera_position", "must be finite",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraPosition(NaN, 0, 5);
        });
    });
  add("raycaster.infinite_focal_point", "must be finite",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraFocalPoint(0, Inf, 0);
        });
    });
  add("raycaster.view_angle_zero", "ViewAngle must be in (0, 180)",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraPosition(0, -5, 0);
          r->SetCameraViewUp(0, 0, 1);
          r->SetViewAngle(0);
        });
    });
  add("raycaster.view_angle_nan", "ViewAngle must be in (0, 180)",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraPosition(0, -5, 0);
          r->SetCameraViewUp(0, 0, 1);
          r->SetViewAngle(NaN);
        });
    });
  add("raycaster.parallel_scale_negative", "ParallelScale must be positive",
    []
    {
      return RayCaster(
        [](vtkPiRayCaster* r)
        {
          r->SetViewMode(vtkPiRayCaster::CAMERA);
          r->SetCameraPosition(0, -5, 0);
          r->SetCameraViewUp(0, 0, 1);
          r->SetParallelProjection(true);
          r->SetParallelScale(-1);
        });
    });
  add("raycaster.singular_tolerance_nan", "SingularTolerance",
    [] { return RayCaster([](vtkPiRayCaster* r) { r->SetSingularTolerance(NaN); }); });
  add("raycaster.input_without_model", "carries no PiSurfaceModel",
    []
    {
      vtkNew<vtkPolyData> input;
      vtkNew<vtkPiRayCaster> caster;
      caster->SetInputData(input);
      caster->Update();
      return Output(caster->GetOutput());
    });
  add("raycaster.input_with_bad_model", "Invalid PiSurfaceModel",
    []
    {
      vtkNew<vtkPolyData> input;
      vtkNew<vtkStringArray> json;
      json->SetName("PiSurfaceModel");
      json->InsertNextValue("{\"pisurf\": 1, \"blending\": ");
      input->GetFieldData()->AddArray(json);
      vtkNew<vtkPiRayCaster> caster;
      caster->SetInputData(input);
      caster->Update();
      return Output(caster->GetOutput());
    });

  // ---- Image triangulator inputs.
  add("triangulator.no_pixel_structure", "has no pixel structure",
    []
    {
      return Triangulator(
        [](vtkPolyData* hits) { hits->GetPointData()->RemoveArray("PixelIndex"); });
    });
  add("triangulator.nan_hit", "non-finite position or normal",
    []
    { return Triangulator([](vtkPolyData* hits) { hits->GetPoints()->SetPoint(3, NaN, 0, 0); }); });
  add("triangulator.bad_views", "PiRayViews",
    []
    {
      return Triangulator(
        [](vtkPolyData* hits)
        {
          auto* views = hits->GetFieldData()->GetArray("PiRayViews");
          if (views)
          {
            for (vtkIdType i = 0; i < views->GetNumberOfValues(); ++i)
            {
              views->SetVariantValue(i, NaN);
            }
          }
        });
    });
  add("triangulator.no_views", "PiRayViews",
    []
    {
      return Triangulator(
        [](vtkPolyData* hits) { hits->GetFieldData()->RemoveArray("PiRayViews"); });
    });
  add("triangulator.pixel_out_of_range", "pixel (",
    []
    {
      return Triangulator(
        [](vtkPolyData* hits)
        {
          auto* pixels = hits->GetPointData()->GetArray("PixelIndex");
          pixels->SetComponent(0, 0, 1e9);
        });
    });
  add("triangulator.bad_model", "Invalid PiSurfaceModel",
    []
    {
      return Triangulator(
        [](vtkPolyData* hits)
        {
          auto* json =
            vtkStringArray::SafeDownCast(hits->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
          json->SetValue(0, "{]");
        });
    });

  // ---- Molecule files.
  add(
    "molecule.missing_file", "Cannot open", [] { return MoleculeReader(TempDir() + "/none.pdb"); });
  add("molecule.empty_file", "No atoms", [] { return MoleculeReader(WriteFile("empty.pdb", "")); });
  add("molecule.binary_garbage", "",
    []
    {
      std::string garbage;
      for (int i = 0; i < 65536; ++i)
      {
        garbage += static_cast<char>((i * 2654435761u >> 13) % 256);
      }
      return MoleculeReader(WriteFile("garbage.pdb", garbage));
    });
  add("molecule.binary_garbage_cif", "Cannot read",
    []
    {
      std::string garbage = "data_x\n";
      for (int i = 0; i < 4096; ++i)
      {
        garbage += static_cast<char>((i * 40503u >> 7) % 256);
      }
      return MoleculeReader(WriteFile("garbage.cif", garbage));
    });
  add("molecule.truncated_record", "",
    []
    {
      const std::string pdb = SmallPdb();
      return MoleculeReader(WriteFile("truncated.pdb", pdb.substr(0, 81 + 40)));
    });
  add("molecule.wrong_columns", "must hold the x coordinate (wrong columns?)",
    []
    {
      // Coordinates shifted by 5 columns (a hand-edited file): not numbers where PDB wants them.
      std::string text;
      for (int i = 0; i < 3; ++i)
      {
        text += "ATOM      1  N   ALA A   1     x0.000y0.000z0.000  1.00  0.00           N\n";
      }
      return MoleculeReader(WriteFile("columns.pdb", text));
    });
  add("molecule.nan_coordinate", "must hold the x coordinate",
    []
    {
      return MoleculeReader(
        WriteFile("nan.pdb", Atom(1, " CA ", "ALA", 1, 0, 0, 0, " C").replace(30, 8, "     nan")));
    });
  add("molecule.cif_nan_coordinate", "not a finite number",
    []
    {
      return MoleculeReader(WriteFile("nan.cif",
        "data_x\nloop_\n_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n"
        "_atom_site.label_atom_id\n_atom_site.label_alt_id\n_atom_site.label_comp_id\n_atom_site."
        "label_asym_id\n"
        "_atom_site.label_seq_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n"
        "_atom_site.occupancy\n_atom_site.B_iso_or_equiv\n_atom_site.auth_seq_id\n"
        "_atom_site.auth_asym_id\n_atom_site.pdbx_PDB_model_num\n"
        "ATOM 1 C CA . ALA A 1 nan 0.0 0.0 1.0 0.0 1 A 1\n"));
    });
  add("molecule.model_out_of_range", "Model 5 requested",
    [] { return MoleculeReader(WriteFile("small.pdb", SmallPdb()), 5); });
  add("molecule.only_waters", "No atoms left",
    []
    {
      return MoleculeReader(WriteFile("waters.pdb",
        Atom(1, " O  ", "HOH", 1, 0, 0, 0, " O", "HETATM") +
          Atom(2, " O  ", "HOH", 2, 3, 0, 0, " O", "HETATM")));
    });
  add("molecule.cif_without_atoms", "No atoms",
    [] { return MoleculeReader(WriteFile("noatoms.cif", "data_x\n_cell.length_a 10\n")); });
  add("molecule.no_file_name", "No FileName",
    []
    {
      vtkNew<vtkPiMoleculeReader> reader;
      reader->Update();
      return Output(reader->GetOutput());
    });

  // ---- Molecular surface settings and molecules.
  add("molsurface.unknown_elements", "warning:No radius in the chosen table for: X (2 atoms)",
    []
    {
      // Atomic number 0 (an unknown element) has no radius in any table: carbon's, said.
      return MoleculeSurface(Molecule({ { 0, 0, 0, 0 }, { 0, 1, 0, 0 } }));
    });
  add("molsurface.empty_molecule", "no atoms", [] { return MoleculeSurface(Molecule({})); });
  add("molsurface.nan_atom", "not a finite number",
    [] {
      return MoleculeSurface(Molecule({ { 6, 0, 0, 0 }, { 6, NaN, 0, 0 } }));
    });
  add("molsurface.nan_blending", "Blending must be a finite number >= 0",
    [] {
      return MoleculeSurface(Molecule(Water), [](vtkPiMoleculeSurface* s) { s->SetBlending(NaN); });
    });
  add("molsurface.negative_blending", "Blending must be a finite number >= 0",
    [] {
      return MoleculeSurface(Molecule(Water), [](vtkPiMoleculeSurface* s) { s->SetBlending(-1); });
    });
  add("molsurface.zero_influence", "InfluenceRadius must be a finite number >= 0.001",
    []
    {
      return MoleculeSurface(Molecule(Water),
        [](vtkPiMoleculeSurface* s)
        {
          s->SetMode(vtkPiMoleculeSurface::LOCAL);
          s->SetInfluenceRadius(0);
        });
    });
  // rho = R in doubles: the factor would jump from f to 1 on the sphere.
  add("molsurface.tiny_influence", "InfluenceRadius must be a finite number >= 0.001",
    []
    {
      return MoleculeSurface(Molecule(Water),
        [](vtkPiMoleculeSurface* s)
        {
          s->SetMode(vtkPiMoleculeSurface::LOCAL);
          s->SetInfluenceRadius(1e-20);
        });
    });
  add("molsurface.negative_spacing", "Spacing must be 0 (automatic) or a positive",
    [] {
      return MoleculeSurface(Molecule(Water), [](vtkPiMoleculeSurface* s) { s->SetSpacing(-1); });
    });
  add("molsurface.tiny_spacing", "MiB; the limit is",
    [] {
      return MoleculeSurface(Molecule(Water), [](vtkPiMoleculeSurface* s) { s->SetSpacing(1e-9); });
    });
  add("molsurface.far_apart_atoms", "",
    []
    {
      // Two atoms 10^7 Å apart: the bounds are huge, the grid must be refused or coarse.
      return MoleculeSurface(Molecule({ { 6, 0, 0, 0 }, { 6, 1e7, 1e7, 1e7 } }),
        [](vtkPiMoleculeSurface* s) { s->SetSpacing(0.5); });
    });
  add("molsurface.huge_coordinates", "",
    [] {
      return MoleculeSurface(Molecule({ { 6, 0, 0, 0 }, { 6, 1e300, 0, 0 } }));
    });
  add("molsurface.polydata_without_numbers", "no point array 'atom_type' or 'AtomicNumber'",
    []
    {
      vtkNew<vtkPolyData> atoms;
      vtkNew<vtkPoints> points;
      points->InsertNextPoint(0, 0, 0);
      atoms->SetPoints(points);
      return MoleculeSurface(atoms);
    });
  add("molsurface.huge_radius_array", "radius",
    []
    {
      vtkNew<vtkPolyData> atoms;
      vtkNew<vtkPoints> points;
      points->InsertNextPoint(0, 0, 0);
      points->InsertNextPoint(1, 0, 0);
      atoms->SetPoints(points);
      vtkNew<vtkDoubleArray> radius;
      radius->SetName("radius");
      radius->InsertNextValue(1.5);
      radius->InsertNextValue(1e300);
      atoms->GetPointData()->AddArray(radius);
      return MoleculeSurface(atoms,
        [](vtkPiMoleculeSurface* s) { s->SetRadiusTable(vtkPiMoleculeSurface::POINT_ARRAY); });
    });
  return c;
}

// One of the cases that are not errors: the million-atom file reads (within time) and
// its Global surface is refused or meshed, never a hang.
int MillionAtoms(CaptureWindow* window)
{
  int failures = 0;
  std::string pdb;
  pdb.reserve(82u * 1000000u);
  for (int i = 0; i < 1000000; ++i)
  {
    pdb += Atom(i + 1, " C  ", "GLY", i / 4 + 1, 1.5 * (i % 100), 1.5 * ((i / 100) % 100),
      1.5 * (i / 10000), " C");
  }
  const std::string path = WriteFile("million.pdb", pdb);
  pdb.clear();
  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkPiMoleculeReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "million atoms: read in " << seconds << " s" << std::endl;
  PI_CHECK(reader->GetOutput()->GetNumberOfAtoms() == 1000000);
  PI_CHECK(seconds < 120);
  window->Text.clear();
  vtkNew<vtkPiMoleculeSurface> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  surface->Update();
  const double total =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "million atoms: surface after " << total
            << " s: " << surface->GetOutput()->GetNumberOfPoints() << " points" << std::endl;
  PI_CHECK(window->Text.find("use Mode = Local") != std::string::npos);
  PI_CHECK(surface->GetOutput()->GetNumberOfPoints() == 0);
  vtksys::SystemTools::RemoveFile(path);
  return failures;
}
}

int TestPiBadInput(int argc, char* argv[])
{
  vtkNew<CaptureWindow> window;
  vtkOutputWindow::SetInstance(window);
  // vtkLogger prints errors to stderr besides the output window: the window has them.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  const std::string only = argc > 1 ? argv[1] : "";

  // A watchdog: a case beyond its budget is a hang; say which and stop.
  std::atomic<double> deadline{ 0 };
  std::string current;
  std::atomic<bool> done{ false };
  std::thread watchdog(
    [&]
    {
      const auto t0 = std::chrono::steady_clock::now();
      while (!done)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        const double now =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (deadline > 0 && now > deadline)
        {
          std::cerr << "HANG: case '" << current << "' exceeded its time budget" << std::endl;
          std::_Exit(2);
        }
      }
    });
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&]
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };

  int failures = 0;
  int count = 0;
  for (const Case& c : Catalogue())
  {
    if (!only.empty() && c.Name.find(only) == std::string::npos)
    {
      continue;
    }
    ++count;
    current = c.Name;
    std::cout << "...  " << c.Name << std::endl;
    window->Text.clear();
    const double start = elapsed();
    deadline = start + c.Seconds;
    Output out = c.Run();
    deadline = 0;
    std::string why;
    // "warning:" cases are documented fallbacks: any output, but said and NaN-free.
    const bool warning = c.Expected.rfind("warning:", 0) == 0;
    const std::string expected = warning ? c.Expected.substr(8) : c.Expected;
    bool ok = Empty(out, why) || (warning && why.find("non-finite") == std::string::npos);
    if (ok)
    {
      why.clear();
    }
    const bool reported = expected.empty() ? window->Text.find("ERROR") != std::string::npos
                                           : window->Text.find(expected) != std::string::npos;
    if (!reported)
    {
      why += (why.empty() ? "" : "; ") + std::string("no message containing '") + expected + "'";
      ok = false;
    }
    if (!ok)
    {
      ++failures;
      std::cerr << "FAIL " << c.Name << ": " << why
                << "\n  captured: " << window->Text.substr(0, 600) << std::endl;
    }
    else
    {
      std::cout << "ok   " << c.Name << " (" << elapsed() - start << " s)" << std::endl;
    }
  }
  if (only.empty() || std::string("molecule.million_atoms").find(only) != std::string::npos)
  {
    current = "molecule.million_atoms";
    deadline = elapsed() + 240;
    failures += MillionAtoms(window);
    deadline = 0;
  }
  done = true;
  watchdog.join();
  vtkOutputWindow::SetInstance(nullptr);
  std::cout << count << " cases, " << failures << " failures" << std::endl;
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
