// SPDX-License-Identifier: BSD-3-Clause
// GUI test of the first Apply of every source and filter of the plugin, through the code
// a ParaView user's Apply button runs: ParaView's properties panel (pqPropertiesPanel)
// and its apply behaviour (pqApplyBehavior: which ports are shown, which inputs are
// hidden, the first camera reset), with the plugin's display defaults
// (pqPiDisplayBehavior). For each: the ports shown, their colouring and opacity, no
// warning or error in the output window, and the camera framing the data shown (not an
// image port in pixel coordinates). The rounded cube with a negative sphere at the
// defaults is compared with a baseline image in which the dent is visible.
// Arguments: the plugin .so, a temporary folder, the models folder, the baselines folder.
#include "PiQtTestUtilities.h"

#include "pqActiveObjects.h"
#include "pqApplyBehavior.h"
#include "pqDataRepresentation.h"
#include "pqInterfaceTracker.h"
#include "pqPVApplicationCore.h"
#include "pqPiParaViewCompat.h"
#include "pqPipelineSource.h"
#include "pqPropertiesPanel.h"
#include "pqPropertyWidget.h"
#include "pqStandardPropertyWidgetInterface.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkSMUncheckedPropertyHelper.h"
#include "vtkTesting.h"

#include <QHBoxLayout>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <sstream>
#include <string>

namespace
{

// A warning or an error among the recorded lines, other than the OpenGL state-cache
// notes of the Mesa driver under Xvfb (not the plugin's).
bool Problems(const std::string& text)
{
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
  {
    const auto has = [&](const char* word) { return line.find(word) != std::string::npos; };
    const bool problem =
      has("Warning") || has("WARN") || has("ERROR") || has("Error") || has("Could not");
    if (problem && !has("vtkOpenGLState") && !has("stack loc") && !has("Error in cache state"))
    {
      return true;
    }
  }
  return false;
}

double Opacity(vtkSMProxy* representation)
{
  return vtkSMPropertyHelper(representation, "Opacity").GetAsDouble();
}

std::string ColorArray(vtkSMProxy* representation)
{
  const char* name =
    vtkSMPropertyHelper(representation, "ColorArrayName").GetInputArrayNameToProcess();
  return pqPiCompat::GetUsingScalarColoring(representation) && name ? name : "";
}

// The representation of `source`'s `port` in `view` when it is visible, else null.
vtkSMProxy* Visible(pqPipelineSource* source, int port, pqView* view)
{
  pqDataRepresentation* representation = source->getRepresentation(port, view);
  return representation && representation->isVisible() ? representation->getProxy() : nullptr;
}

bool Categorical(vtkSMProxy* representation)
{
  vtkSMProxy* lut = vtkSMPropertyHelper(representation, "LookupTable", true).GetAsProxy();
  return lut && vtkSMPropertyHelper(lut, "IndexedLookup").GetAsInt() == 1;
}

vtkRenderer* Renderer(pqRenderView* view)
{
  return view->getRenderViewProxy()->GetRenderer();
}

// The camera looks at the centre of what is shown, and what is shown is the data of
// `expected` (bounds within 1 % of their size), not more.
bool Framed(pqRenderView* view, const double expected[6], std::string& why)
{
  double shown[6];
  Renderer(view)->ComputeVisiblePropBounds(shown);
  double size = 0;
  for (int k = 0; k < 3; ++k)
  {
    size = std::max(size, expected[2 * k + 1] - expected[2 * k]);
  }
  double focal[3];
  Renderer(view)->GetActiveCamera()->GetFocalPoint(focal);
  for (int k = 0; k < 6; ++k)
  {
    if (std::abs(shown[k] - expected[k]) > 0.01 * size)
    {
      why = "shown bounds " + std::to_string(shown[k]) + " where the data has " +
        std::to_string(expected[k]);
      return false;
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    if (std::abs(focal[k] - 0.5 * (shown[2 * k] + shown[2 * k + 1])) > 0.01 * size)
    {
      why = "the camera looks at " + Str3(focal) + ", not the centre of the data";
      return false;
    }
  }
  return true;
}
}

int main(int argc, char* argv[])
{
  if (argc < 5)
  {
    std::cerr << "usage: TestPiFirstApplyGUI <plugin .so> <temporary folder> <models folder> "
                 "<baselines folder>\n";
    return EXIT_FAILURE;
  }
  const std::string temporary = argv[2], models = argv[3], baselines = argv[4];
  TestApplication<pqPVApplicationCore> application(argv[0]);
  pqPVApplicationCore& core = application.Application;
  core.interfaceTracker()->addInterface(new pqStandardPropertyWidgetInterface(&core));
  vtkNew<OutputRecorder> output;
  vtkOutputWindow::SetInstance(output);
  pqObjectBuilder* builder = core.getObjectBuilder();
  pqServer* server = StartSession(builder, argv[1]);
  if (!server)
  {
    return EXIT_FAILURE;
  }
  pqActiveObjects::instance().setActiveServer(server);
  QWidget window;
  auto* layout = new QHBoxLayout(&window);
  auto* panel = new pqPropertiesPanel(&window);
  layout->addWidget(panel);
  pqApplyBehavior behavior;
  behavior.registerPanel(panel);
  window.resize(1200, 700);
  window.show();

  pqRenderView* view = nullptr;
  // A fresh view, as a new ParaView session has.
  auto newView = [&]()
  {
    builder->destroySources(server);
    if (view)
    {
      layout->removeWidget(view->widget());
      builder->destroy(view);
    }
    view = CreateRenderView(builder, server);
    layout->addWidget(view->widget(), 1);
    pqActiveObjects::instance().setActiveView(view);
    QCoreApplication::processEvents();
  };
  // What the user's Apply does for a new source or filter.
  auto apply = [&](pqPipelineSource* source)
  {
    output->Text.clear();
    pqActiveObjects::instance().setActiveSource(source);
    QCoreApplication::processEvents();
    panel->apply();
    QCoreApplication::processEvents();
    view->forceRender();
  };
  auto bounds = [](pqPipelineSource* source, int port, double b[6])
  { vtkSMSourceProxy::SafeDownCast(source->getProxy())->GetDataInformation(port)->GetBounds(b); };
  // Nothing reached the output window since the last apply.
  auto expectQuiet = [&](const char* what) {
    CHECK(!Problems(output->Text), what << ": nothing in the output window:\n" << output->Text);
  };
  std::string why;

  // Pi Surface: the paper's Figure 1(b), translucent grey over its coloured primitives.
  newView();
  {
    pqPipelineSource* surface = builder->createSource("sources", "PiSurface", server);
    apply(surface);
    vtkSMProxy* pi = Visible(surface, 0, view);
    vtkSMProxy* primitives = Visible(surface, 1, view);
    CHECK(pi && Opacity(pi) < 1 && ColorArray(pi).empty(), "Pi Surface: translucent grey");
    CHECK(primitives && Opacity(primitives) == 1 && ColorArray(primitives) == "Factor" &&
        Categorical(primitives),
      "Pi Surface: its primitives opaque, one colour per Factor");
    expectQuiet("Pi Surface");
    double b[6];
    bounds(surface, 0, b);
    CHECK(Framed(view, b, why), "Pi Surface: the camera frames it: " << why);
  }

  // The model reader on the rounded cube with a negative sphere: the Π-surface lies inside
  // the cube, so it is opaque and its dent shows under the translucent primitives.
  newView();
  {
    pqPipelineSource* reader = builder->createReader("sources", "PiSurfaceModelReader",
      { QString::fromStdString(models + "/rounded_cube_sphere_2.pisurf") }, server);
    apply(reader);
    vtkSMProxy* pi = Visible(reader, 0, view);
    vtkSMProxy* primitives = Visible(reader, 1, view);
    CHECK(pi && Opacity(pi) == 1 && ColorArray(pi).empty(),
      "rounded cube: the Π-surface is opaque grey (opacity " << (pi ? Opacity(pi) : -1) << ")");
    CHECK(primitives && Opacity(primitives) < 1 && ColorArray(primitives) == "Factor",
      "rounded cube: the primitives are translucent, coloured by Factor");
    expectQuiet("rounded cube");
    double b[6];
    bounds(reader, 1, b);
    CHECK(Framed(view, b, why), "rounded cube: the camera frames it: " << why);
    // The picture, from a direction that shows the dent beside the sphere.
    window.resize(1000, 640);
    QCoreApplication::processEvents();
    vtkCamera* camera = Renderer(view)->GetActiveCamera();
    const double centre[3] = { 0.25, 0, 0 };
    camera->SetFocalPoint(centre);
    camera->SetPosition(centre[0] + 0.6, centre[1] - 1.2, centre[2] + 0.5);
    camera->SetViewUp(0, 0, 1);
    view->resetCamera();
    view->forceRender();
    vtkNew<vtkTesting> testing;
    testing->AddArgument("-T");
    testing->AddArgument(temporary.c_str());
    testing->AddArgument("-V");
    testing->AddArgument((baselines + "/FirstApply.rounded_cube_sphere_2.png").c_str());
    testing->SetRenderWindow(view->getRenderViewProxy()->GetRenderWindow());
    CHECK(testing->RegressionTest(0.15) == vtkTesting::PASSED,
      "rounded cube: the picture matches its baseline (see " << temporary << ")");
  }

  // Pi Primitive: opaque, in a palette colour, with its widget.
  newView();
  pqPipelineSource* a = builder->createSource("sources", "PiPrimitive", server);
  apply(a);
  {
    vtkSMProxy* shown = Visible(a, 0, view);
    double colour[3] = { 1, 1, 1 };
    if (shown)
    {
      vtkSMPropertyHelper(shown, "DiffuseColor").Get(colour, 3);
    }
    CHECK(shown && Opacity(shown) == 1 && !(colour[0] == colour[1] && colour[1] == colour[2]),
      "Pi Primitive: opaque, in a colour of the palette");
    CHECK(FindWidget(view->getProxy(), "SphereWidgetRepresentation", true),
      "Pi Primitive: its sphere widget is shown");
    expectQuiet("Pi Primitive");
  }
  // A refused value: the field is marked with the reason, the message names the source,
  // and the last valid surface stays.
  {
    auto* placement = panel->findChild<pqPropertyWidget*>("pi_primitive_placement");
    auto* sphere =
      placement ? placement->findChild<pqPropertyWidget*>("InteractiveSphere") : nullptr;
    vtkSMUncheckedPropertyHelper(a->getProxy(), "Radius").Set(-0.1);
    QTest::qWait(50);
    CHECK(sphere && sphere->styleSheet().contains("background") &&
        sphere->toolTip().contains("radius must be a positive finite number"),
      "a negative radius is marked before Apply, with the reason");
    output->Text.clear();
    panel->apply();
    QCoreApplication::processEvents();
    const std::string name = a->getSMName().toStdString();
    CHECK(output->Text.find("radius must be a positive") != std::string::npos &&
        output->Text.find(name) != std::string::npos,
      "the refusal names the source '" << name << "':\n"
                                       << output->Text);
    CHECK(sphere && sphere->styleSheet().contains("background"),
      "after Apply the refused radius stays marked");
    CHECK(
      vtkSMSourceProxy::SafeDownCast(a->getProxy())->GetDataInformation(0)->GetNumberOfPoints() > 0,
      "the last valid sphere stays");
    vtkSMUncheckedPropertyHelper(a->getProxy(), "Radius").Set(1);
    panel->apply();
    QTest::qWait(50);
    CHECK(sphere && !sphere->styleSheet().contains("background"), "a valid radius is unmarked");
    // A parameter outside the widget: the torus's tube radius.
    vtkSMUncheckedPropertyHelper(a->getProxy(), "Type").Set(3);
    vtkSMUncheckedPropertyHelper(a->getProxy(), "MinorRadius").Set(-1);
    QTest::qWait(50);
    auto* minor = panel->findChild<pqPropertyWidget*>("MinorRadius");
    CHECK(minor && minor->styleSheet().contains("background") &&
        minor->toolTip().contains("minor_radius"),
      "a negative tube radius marks the MinorRadius field");
    panel->reset();
    QTest::qWait(50);
    CHECK(minor && !minor->styleSheet().contains("background"), "Reset unmarks it");
  }

  // Pi Product of three primitives: the inputs stay shown, the product over them.
  pqPipelineSource* b = builder->createSource("sources", "PiPrimitive", server);
  vtkSMPropertyHelper(b->getProxy(), "Center").Set(0, 1.5);
  apply(b);
  pqPipelineSource* c = builder->createSource("sources", "PiPrimitive", server);
  vtkSMPropertyHelper(c->getProxy(), "Center").Set(1, 1.5);
  apply(c);
  {
    QMap<QString, QList<pqOutputPort*>> inputs;
    inputs["Input"] = { a->getOutputPort(0), b->getOutputPort(0), c->getOutputPort(0) };
    pqPipelineSource* product = builder->createFilter("filters", "PiProduct", inputs, server);
    apply(product);
    CHECK(Visible(a, 0, view) && Visible(b, 0, view) && Visible(c, 0, view),
      "Pi Product: its three inputs stay shown");
    vtkSMProxy* pi = Visible(product, 0, view);
    CHECK(pi && Opacity(pi) < 1 && ColorArray(pi).empty(),
      "Pi Product: translucent grey over its inputs");
    CHECK(!Visible(product, 1, view), "Pi Product: its empty Primitives port is not shown");
    expectQuiet("Pi Product");
  }

  // Pi Ray Cast of a Pi Surface: the hits, not the image in pixel coordinates.
  newView();
  {
    pqPipelineSource* surface = builder->createSource("sources", "PiSurface", server);
    apply(surface);
    pqPipelineSource* cast = builder->createFilter("filters", "PiRayCast", surface);
    vtkSMPropertyHelper(cast->getProxy(), "Resolution")
      .Set(std::array<int, 2>{ 128, 128 }.data(), 2);
    apply(cast);
    CHECK(Visible(cast, 0, view), "Pi Ray Cast: the hits are shown");
    CHECK(!Visible(cast, 1, view), "Pi Ray Cast: the image port is not shown");
    expectQuiet("Pi Ray Cast");
    double hits[6];
    bounds(surface, 0, hits); // the hits lie on the surface, within its box
    double shown[6];
    Renderer(view)->ComputeVisiblePropBounds(shown);
    CHECK(shown[1] - shown[0] < 1.01 * (hits[1] - hits[0]),
      "Pi Ray Cast: nothing larger than the surface is shown (width " << shown[1] - shown[0]
                                                                      << ")");
    pqPipelineSource* mesh = builder->createFilter("filters", "ImageBasedTriangulation", cast);
    apply(mesh);
    CHECK(Visible(mesh, 0, view), "Image Based Triangulation: shown");
    expectQuiet("Image Based Triangulation");
    pqPipelineSource* sample = builder->createFilter("filters", "PiSampleFunction", surface);
    vtkSMPropertyHelper(sample->getProxy(), "SampleDimensions")
      .Set(std::array<int, 3>{ 24, 24, 24 }.data(), 3);
    apply(sample);
    CHECK(Visible(sample, 0, view), "Pi Sample Function: shown");
    expectQuiet("Pi Sample Function");
  }

  // A protein: AtomicNumber in CPK colours, categories not a continuous map.
  newView();
  {
    pqPipelineSource* molecule = builder->createReader(
      "sources", "PiMoleculeReader", { QString("/usr/share/freesasa/test-data/1ubq.pdb") }, server);
    apply(molecule);
    pqPipelineSource* surface = builder->createFilter("filters", "MolecularPiSurface", molecule);
    apply(surface);
    CHECK(Visible(surface, 0, view), "Molecular Pi Surface: shown");
    expectQuiet("Molecular Pi Surface");
    vtkNew<vtkSMTransferFunctionManager> manager;
    vtkSMProxy* lut = manager->GetColorTransferFunction(
      "AtomicNumber", surface->getProxy()->GetSessionProxyManager());
    CHECK(lut && vtkSMPropertyHelper(lut, "IndexedLookup").GetAsInt() == 1,
      "AtomicNumber is coloured by element (categories)");
    if (lut)
    {
      // Oxygen red, nitrogen blue: the CPK convention.
      vtkSMPropertyHelper annotations(lut, "Annotations");
      vtkSMPropertyHelper colours(lut, "IndexedColors");
      bool oxygenRed = false, nitrogenBlue = false;
      for (unsigned int i = 0; 2 * i + 1 < annotations.GetNumberOfElements(); ++i)
      {
        const std::string value = annotations.GetAsString(2 * i);
        const double r = colours.GetAsDouble(3 * i), bl = colours.GetAsDouble(3 * i + 2);
        oxygenRed |= value == "8" && r > 0.9 && bl < 0.2;
        nitrogenBlue |= value == "7" && bl > 0.9 && r < 0.3;
      }
      CHECK(oxygenRed && nitrogenBlue, "AtomicNumber: O red, N blue");
    }
  }

  window.hide();
  builder->destroySources(server);
  builder->destroyAllProxies(server);
  builder->removeServer(server);
  vtkOutputWindow::SetInstance(nullptr);
  std::cerr << (Failures ? "FAILED" : "passed") << " (" << Failures << " failures)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
