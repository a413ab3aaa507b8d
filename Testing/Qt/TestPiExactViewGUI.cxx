// SPDX-License-Identifier: BSD-3-Clause
// GUI test of the Pi Exact Surface representation under Xvfb, in a small ParaView
// client: a Pi Product of two spheres (Pi Primitive) shown in a render view, switched to
// the representation "Pi Exact Surface" (its display's Representation property, as the
// Representation menu sets it); the second sphere's properties panel beside the view,
// its sphere widget moved and dragged, then Apply. The picture changes, the exact view
// cast again, and Pi Product's output is the model alone: the edit reached the picture
// without any mesh computed. Switched back to Surface, the product meshes again.
#include "PiQtTestUtilities.h"

#include "pqInterfaceTracker.h"
#include "pqObjectBuilder.h"
#include "pqPVApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqProxyWidget.h"
#include "pqRenderView.h"
#include "pqStandardPropertyWidgetInterface.h"
#include "vtkAbstractWidget.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkPVCompositeRepresentation.h"
#include "vtkPiExactSurfaceMapper.h"
#include "vtkPiExactSurfaceRepresentation.h"
#include "vtkPiModelMesher.h"
#include "vtkRenderWindow.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <QHBoxLayout>

#include <array>
#include <cstdlib>
#include <vector>

namespace
{
// The view's picture as bytes.
std::vector<unsigned char> Picture(pqRenderView* view)
{
  view->forceRender();
  vtkRenderWindow* window = vtkSMViewProxy::SafeDownCast(view->getProxy())->GetRenderWindow();
  std::vector<unsigned char> bytes;
  if (window)
  {
    const int* size = window->GetSize();
    vtkNew<vtkUnsignedCharArray> pixels;
    window->GetRGBACharPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
    bytes.assign(pixels->GetPointer(0), pixels->GetPointer(0) + pixels->GetDataSize());
  }
  return bytes;
}

// The exact mapper of a display whose active representation is Pi Exact Surface.
vtkPiExactSurfaceMapper* ExactMapper(vtkSMProxy* display)
{
  auto* composite = vtkPVCompositeRepresentation::SafeDownCast(display->GetClientSideObject());
  auto* exact = composite
    ? vtkPiExactSurfaceRepresentation::SafeDownCast(composite->GetActiveRepresentation())
    : nullptr;
  return exact ? exact->GetExactMapper() : nullptr;
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestPiExactViewGUI <PiSurfaces plugin .so> [temporary folder]\n";
    return EXIT_FAILURE;
  }
  TestApplication<pqPVApplicationCore> application(argv[0]);
  pqPVApplicationCore& core = application.Application;
  core.interfaceTracker()->addInterface(new pqStandardPropertyWidgetInterface(&core));
  pqObjectBuilder* builder = core.getObjectBuilder();
  pqServer* server = StartSession(builder, argv[1]);
  if (!server)
  {
    return EXIT_FAILURE;
  }
  QWidget window;
  auto* layout = new QHBoxLayout(&window);
  pqRenderView* view = CreateRenderView(builder, server);
  if (!view)
  {
    return EXIT_FAILURE;
  }
  auto* viewProxy = vtkSMViewProxy::SafeDownCast(view->getProxy());
  vtkSMPropertyHelper(viewProxy, "OrientationAxesVisibility").Set(0);

  pqPipelineSource* first = builder->createSource("sources", "PiPrimitive", server);
  pqPipelineSource* second = builder->createSource("sources", "PiPrimitive", server);
  auto* a = vtkSMSourceProxy::SafeDownCast(first->getProxy());
  auto* b = vtkSMSourceProxy::SafeDownCast(second->getProxy());
  vtkSMPropertyHelper(a, "Center").Set(std::array<double, 3>{ -0.6, 0, 0 }.data(), 3);
  vtkSMPropertyHelper(b, "Center").Set(std::array<double, 3>{ 0.6, 0, 0 }.data(), 3);
  a->UpdateVTKObjects();
  b->UpdateVTKObjects();
  pqPipelineSource* productSource = builder->createFilter("filters", "PiProduct",
    QMap<QString, QList<pqOutputPort*>>{
      { "Input", { first->getOutputPort(0), second->getOutputPort(0) } } },
    server);
  auto* product = vtkSMSourceProxy::SafeDownCast(productSource->getProxy());
  vtkSMPropertyHelper(product, "Blending").Set(0.3);
  vtkSMPropertyHelper(product, "Resolution").Set(64);
  product->UpdateVTKObjects();
  product->UpdatePipeline();
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMProxy* display = controller->Show(product, 0, viewProxy);
  CHECK(display, "Pi Product is shown");
  if (!display)
  {
    return EXIT_FAILURE;
  }
  vtkSMPropertyHelper(display, "Representation").Set("Pi Exact Surface");
  display->UpdateVTKObjects();

  auto* panel = new pqProxyWidget(b, &window);
  panel->setApplyChangesImmediately(false);
  panel->setView(view);
  layout->addWidget(panel);
  layout->addWidget(view->widget(), 1);
  window.resize(1000, 700);
  window.show();
  panel->updatePanel();
  CHECK(QTest::qWaitForWindowExposed(&window), "the window is shown");
  view->resetDisplay();
  const std::vector<unsigned char> before = Picture(view);
  auto* mesher = vtkPiModelMesher::SafeDownCast(product->GetClientSideObject());
  vtkPiExactSurfaceMapper* mapper = ExactMapper(display);
  CHECK(mesher && mapper, "the product's algorithm and the exact view's mapper are found");
  const int casts = mapper ? mapper->GetCastCount() : 0;

  // The second sphere's widget moved and dragged, then Apply.
  vtkSMNewWidgetRepresentationProxy* sphere =
    FindWidget(viewProxy, "SphereWidgetRepresentation", true);
  CHECK(sphere, "the Pi Primitive panel shows its sphere widget in the view");
  if (sphere && mesher && mapper)
  {
    vtkSMPropertyHelper(sphere, "Center").Set(std::array<double, 3>{ 1.3, 0, 0.2 }.data(), 3);
    Drag(sphere);
    panel->apply();
    b->UpdateVTKObjects();
    const std::vector<unsigned char> after = Picture(view);
    double center[3];
    vtkSMPropertyHelper(b, "Center").Get(center, 3);
    CHECK(Near3(center, 1.3, 0, 0.2), "the drag moved the sphere: centre " << Str3(center));
    CHECK(!before.empty() && before.size() == after.size() && before != after,
      "the exact picture changed after the drag");
    CHECK(mapper->GetCastCount() > casts, "the exact view cast again after the drag");
    vtkDataObject* output = mesher->GetOutputDataObject(0);
    CHECK(mesher->GetLastOutputModelOnly() && output && output->GetNumberOfElements(1) == 0,
      "Pi Product computed no mesh for the exact view: model only "
        << mesher->GetLastOutputModelOnly() << ", "
        << (output ? output->GetNumberOfElements(1) : -1) << " cells");

    // Back to Surface: the mesh is computed again.
    vtkSMPropertyHelper(display, "Representation").Set("Surface");
    display->UpdateVTKObjects();
    Picture(view);
    output = mesher->GetOutputDataObject(0);
    CHECK(!mesher->GetLastOutputModelOnly() && output && output->GetNumberOfElements(1) > 1000,
      "shown as Surface, Pi Product meshes again: "
        << (output ? output->GetNumberOfElements(1) : -1) << " cells");
  }

  window.hide();
  delete panel;
  builder->destroy(productSource);
  builder->destroy(second);
  builder->destroy(first);
  builder->destroy(view);
  builder->removeServer(server);
  std::cerr << (Failures ? "FAILED" : "passed") << " (" << Failures << " failures)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
