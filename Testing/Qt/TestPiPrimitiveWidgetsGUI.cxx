// SPDX-License-Identifier: BSD-3-Clause
// GUI test of the Pi Primitive source's 3D widgets under Xvfb: its properties panel
// (pqProxyWidget) beside a render view, in a small ParaView client. The panel shows one
// of ParaView's interactive widgets per type (found in the view's HiddenRepresentations):
// an ellipsoid's box is placed at Center, scaled by Radii and turned by Orientation, and
// turning the box (its proxy set, then the interaction events its VTK widget fires
// during a drag) turns the ellipsoid once applied; a torus gets a cylinder through its
// tube's centre line (Center, Axis, MajorRadius), whose radius edits MajorRadius; a cone
// gets a plane through its apex across its axis, whose normal edits Axis. Then every
// type, picked in the panel before Apply: its Placement group shows the expected widget,
// the view shows that widget and no other, and only that type's own parameters show;
// the sphere's widget, dragged, moves the sphere. Writes PiPrimitiveBox.png (the
// user guide's picture) into the picture folder when given one.
#include "PiModel.h"
#include "PiQtTestUtilities.h"

#include "pqInterfaceTracker.h"
#include "pqObjectBuilder.h"
#include "pqPVApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqPropertyWidget.h"
#include "pqProxyWidget.h"
#include "pqRenderView.h"
#include "pqStandardPropertyWidgetInterface.h"
#include "vtkAbstractWidget.h"
#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMUncheckedPropertyHelper.h"
#include "vtkSMViewProxy.h"
#include "vtkStringArray.h"

#include <QHBoxLayout>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <vector>

namespace
{
// The model the source's output carries (its PiSurfaceModel field data).
bool OutputModel(vtkSMSourceProxy* proxy, pisurf::Model& model)
{
  proxy->UpdatePipeline();
  auto* algorithm = vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject());
  vtkDataObject* output = algorithm ? algorithm->GetOutputDataObject(0) : nullptr;
  auto* json = output
    ? vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("PiSurfaceModel"))
    : nullptr;
  std::string error;
  return json && json->GetNumberOfValues() == 1 &&
    pisurf::ParseModel(json->GetValue(0), model, error) && model.Primitives.size() == 1;
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestPiPrimitiveWidgetsGUI <PiSurfaces plugin .so> [picture folder]\n";
    return EXIT_FAILURE;
  }
  // (pqPVApplicationCore: the handle widget needs its selection manager)
  TestApplication<pqPVApplicationCore> application(argv[0]);
  pqPVApplicationCore& core = application.Application;
  // ParaView's own property widgets (the interactive box, cylinder and plane) and
  // decorators, as the ParaView client registers them.
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
  vtkSMProxy* viewProxy = view->getProxy();
  pqPipelineSource* source = builder->createSource("sources", "PiPrimitive", server);
  auto* proxy = vtkSMSourceProxy::SafeDownCast(source->getProxy());
  vtkSMPropertyHelper(proxy, "Type").Set(1); // Ellipsoid
  const double radii[3] = { 1.5, 1, 0.5 }, orientation[3] = { 0, 0, 30 };
  vtkSMPropertyHelper(proxy, "Radii").Set(radii, 3);
  vtkSMPropertyHelper(proxy, "Orientation").Set(orientation, 3);
  vtkSMPropertyHelper(proxy, "Resolution").Set(24);
  proxy->UpdateVTKObjects();
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  controller->Show(proxy, 0, vtkSMViewProxy::SafeDownCast(viewProxy));

  auto* panel = new pqProxyWidget(proxy, &window);
  panel->setApplyChangesImmediately(false);
  panel->setView(view);
  layout->addWidget(panel);
  layout->addWidget(view->widget(), 1);
  window.resize(1000, 700);
  window.show();
  // As ParaView's properties panel does: the decorators hide the other types' widgets.
  panel->updatePanel();
  CHECK(QTest::qWaitForWindowExposed(&window), "the window is shown");
  auto apply = [&]()
  {
    panel->apply();
    proxy->UpdateVTKObjects();
    view->forceRender();
  };
  apply();
  // Another type: the panel shows that type's widget (as after an edit in ParaView).
  auto showType = [&](int type)
  {
    vtkSMPropertyHelper(proxy, "Type").Set(type);
    proxy->UpdateVTKObjects();
    panel->updatePanel();
    view->forceRender();
    QCoreApplication::processEvents();
  };

  // The ellipsoid's box: Center, Radii and Orientation.
  vtkSMNewWidgetRepresentationProxy* box = FindWidget(viewProxy, "BoxWidgetRepresentation");
  const int shown = CountWidgets(viewProxy, true);
  CHECK(box && Shown(box) && shown == 1,
    "an ellipsoid shows a box widget, and only that (" << shown << " shown)");
  if (box)
  {
    double rotation[3], scale[3];
    box->UpdatePropertyInformation();
    vtkSMPropertyHelper(box, "RotationInfo").Get(rotation, 3);
    vtkSMPropertyHelper(box, "ScaleInfo").Get(scale, 3);
    CHECK(Near3(rotation, 0, 0, 30, 1e-6) && Near3(scale, 1.5, 1, 0.5, 1e-6),
      "the box is turned by Orientation and scaled by Radii: rotation "
        << Str3(rotation) << ", scale " << Str3(scale));
    // Turning the box turns the ellipsoid.
    const double turned[3] = { 0, 0, 75 };
    vtkSMPropertyHelper(box, "Rotation").Set(turned, 3);
    Drag(box);
    apply();
    double now[3];
    vtkSMPropertyHelper(proxy, "Orientation").Get(now, 3);
    CHECK(Near3(now, 0, 0, 75, 1e-6), "turning the box sets Orientation: " << Str3(now));
    pisurf::Model model;
    const bool parsed = OutputModel(proxy, model);
    const pisurf::PrimitiveSpec& e =
      model.Primitives.empty() ? pisurf::PrimitiveSpec() : model.Primitives[0];
    CHECK(parsed && e.Orient == pisurf::Orientation::Rotation &&
        Near(e.RotationAngle * (e.RotationAxis[2] > 0 ? 1 : -1), 75, 1e-6) &&
        Near(std::abs(e.RotationAxis[2]), 1, 1e-9),
      "the output's model is the ellipsoid turned 75 degrees about z (angle "
        << e.RotationAngle << ", axis " << Str3(e.RotationAxis) << ")");
    // The user guide's picture: the panel and the turned box around the turned ellipsoid.
    if (argc > 2)
    {
      window.resize(1000, 640);
      QCoreApplication::processEvents();
      view->resetCamera();
      view->forceRender();
      QCoreApplication::processEvents();
      window.grab().save(QString(argv[2]) + "/PiPrimitiveBox.png");
    }
  }

  // A torus: a cylinder through the tube's centre line.
  const double axis[3] = { 0, 1, 0 };
  vtkSMPropertyHelper(proxy, "Axis").Set(axis, 3);
  vtkSMPropertyHelper(proxy, "MajorRadius").Set(1.25);
  vtkSMPropertyHelper(proxy, "Orientation").Set(std::array<double, 3>{ 0, 0, 0 }.data(), 3);
  showType(3);
  vtkSMNewWidgetRepresentationProxy* cylinder =
    FindWidget(viewProxy, "ImplicitCylinderWidgetRepresentation", true);
  CHECK(cylinder && Shown(cylinder), "a torus shows a cylinder widget");
  CHECK(!box || !Shown(box), "and no box");
  if (cylinder)
  {
    double widgetAxis[3];
    vtkSMPropertyHelper(cylinder, "Axis").Get(widgetAxis, 3);
    const double radius = vtkSMPropertyHelper(cylinder, "Radius").GetAsDouble();
    CHECK(Near3(widgetAxis, 0, 1, 0) && Near(radius, 1.25),
      "the cylinder has the torus's axis and major radius: " << Str3(widgetAxis) << ", " << radius);
    vtkSMPropertyHelper(cylinder, "Radius").Set(0.8);
    Drag(cylinder);
    apply();
    const double major = vtkSMPropertyHelper(proxy, "MajorRadius").GetAsDouble();
    CHECK(Near(major, 0.8, 1e-9), "the cylinder's radius sets MajorRadius: " << major);
  }

  // A cone: a plane through the apex across the axis.
  showType(6);
  vtkSMNewWidgetRepresentationProxy* plane =
    FindWidget(viewProxy, "DisplaySizedImplicitPlaneWidgetRepresentation", true);
  CHECK(plane && Shown(plane), "a cone shows a plane widget");
  if (plane)
  {
    double normal[3];
    vtkSMPropertyHelper(plane, "Normal").Get(normal, 3);
    CHECK(Near3(normal, 0, 1, 0), "the plane's normal is the cone's axis: " << Str3(normal));
    const double tilted[3] = { 1, 0, 0 };
    vtkSMPropertyHelper(plane, "Normal").Set(tilted, 3);
    Drag(plane);
    apply();
    double now[3];
    vtkSMPropertyHelper(proxy, "Axis").Get(now, 3);
    CHECK(Near3(now, 1, 0, 0, 1e-9), "the plane's normal sets the cone's Axis: " << Str3(now));
  }

  // Every type, as a user picks it in the Type menu before Apply (the unchecked value):
  // its placement widget with the parameters that widget edits, its other parameters,
  // and nothing of another type's.
  struct TypeView
  {
    const char* Name;
    const char* Panel;              // ParaView's panel widget in the Placement group
    const char* Widget;             // the representation of its 3D widget
    std::vector<const char*> Shown; // its parameters outside the placement widget
  };
  const std::vector<TypeView> types = {
    { "Sphere", "InteractiveSphere", "SphereWidgetRepresentation", {} },
    { "Ellipsoid", "InteractiveBox", "BoxWidgetRepresentation", {} },
    { "Superellipsoid", "InteractiveBox", "BoxWidgetRepresentation", { "Exponent" } },
    { "Torus", "InteractiveCylinder", "ImplicitCylinderWidgetRepresentation", { "MinorRadius" } },
    { "Plane", "InteractivePlane", "DisplaySizedImplicitPlaneWidgetRepresentation", {} },
    { "Cylinder", "InteractiveCylinder", "ImplicitCylinderWidgetRepresentation", {} },
    { "Cone", "InteractivePlane", "DisplaySizedImplicitPlaneWidgetRepresentation", { "Angle" } },
    { "Hyperboloid1", "InteractiveBox", "BoxWidgetRepresentation", {} },
    { "Hyperboloid2", "InteractiveBox", "BoxWidgetRepresentation", {} },
    { "Paraboloid", "InteractiveBox", "BoxWidgetRepresentation", {} },
    { "HyperbolicParaboloid", "InteractiveBox", "BoxWidgetRepresentation", {} },
    { "Polynomial", "InteractiveHandle", "HandleWidgetRepresentation", { "Expression" } },
  };
  const std::vector<const char*> typeOnly = { "Exponent", "MinorRadius", "Angle", "Expression" };
  for (size_t type = 0; type < types.size(); ++type)
  {
    const TypeView& expected = types[type];
    vtkSMUncheckedPropertyHelper(proxy, "Type").Set(static_cast<int>(type));
    panel->updatePanel();
    QCoreApplication::processEvents();
    view->forceRender();
    auto* placement = panel->findChild<pqPropertyWidget*>("pi_primitive_placement");
    auto* current = placement ? placement->findChild<pqPropertyWidget*>(expected.Panel) : nullptr;
    CHECK(placement && placement->isVisible() && current && current->isVisible(),
      expected.Name << ": the Placement group shows ParaView's " << expected.Panel);
    vtkSMNewWidgetRepresentationProxy* widget = FindWidget(viewProxy, expected.Widget, true);
    const int count = CountWidgets(viewProxy, true);
    CHECK(widget && count == 1,
      expected.Name << ": the view shows its " << expected.Widget << " and no other widget ("
                    << count << " shown)");
    for (const char* name : typeOnly)
    {
      const bool wanted =
        std::find_if(expected.Shown.begin(), expected.Shown.end(),
          [&](const char* n) { return std::string(n) == name; }) != expected.Shown.end();
      auto* w = panel->findChild<pqPropertyWidget*>(name);
      CHECK(w && w->isVisible() == wanted,
        expected.Name << ": " << name << (wanted ? " is shown" : " is hidden"));
    }
  }
  // The sphere's widget places the sphere: moving it and Apply move the output.
  vtkSMUncheckedPropertyHelper(proxy, "Type").Set(0);
  panel->updatePanel();
  QCoreApplication::processEvents();
  if (vtkSMNewWidgetRepresentationProxy* sphere =
        FindWidget(viewProxy, "SphereWidgetRepresentation", true))
  {
    vtkSMPropertyHelper(sphere, "Center").Set(std::array<double, 3>{ 0.5, -1, 2 }.data(), 3);
    vtkSMPropertyHelper(sphere, "Radius").Set(0.75);
    Drag(sphere);
    apply();
    pisurf::Model model;
    const bool parsed = OutputModel(proxy, model);
    const pisurf::PrimitiveSpec& s =
      model.Primitives.empty() ? pisurf::PrimitiveSpec() : model.Primitives[0];
    CHECK(parsed && s.Type == pisurf::PrimitiveType::Sphere && Near3(s.Center, 0.5, -1, 2) &&
        Near(s.Radius, 0.75),
      "dragging the sphere widget places the sphere: centre " << Str3(s.Center) << ", radius "
                                                              << s.Radius);
  }

  window.hide();
  delete panel;
  builder->destroy(source);
  builder->destroy(view);
  builder->removeServer(server);
  std::cerr << (Failures ? "FAILED" : "passed") << " (" << Failures << " failures)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
