// SPDX-License-Identifier: BSD-3-Clause
// GUI test of the primitive editor's 3D widget (pqPiPrimitiveListWidget with
// pqPiPrimitive3DWidget) under Xvfb: a small ParaView client (like
// TestPiPrimitiveEditorGUI) with a render view beside the Pi Surface's properties panel.
// The selected row gets ParaView's sphere widget (found in the view's
// HiddenRepresentations, not through the editor's API) at the row's centre and radius;
// a move of the widget (its proxy changed and its VTK widget's interaction events fired,
// then real mouse drags through the view's interactor: the left button moves the sphere,
// the right button scales it) edits the row and, on Apply, the
// Model JSON; a typed radius moves the widget; another row, an ellipsoid (box widget:
// scaled, turned, and turned by a typed rotation), a
// torus (handle), the "Show 3D widget" checkbox, the hidden panel, a change of the
// property from outside, a destroyed view, another view and a deleted editor all do what
// the editor's documentation says.
#include "PiModel.h"
#include "PiQtTestUtilities.h"

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqPipelineSource.h"
#include "pqProxyWidget.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerResource.h"
#include "vtkAbstractWidget.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSMNewWidgetRepresentationProxy.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPluginManager.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"

#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPointer>
#include <QTableWidget>
#include <QTest>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
bool Parse(vtkSMProxy* proxy, pisurf::Model& model)
{
  std::string error;
  if (!pisurf::ParseModel(ModelText(proxy), model, error))
  {
    std::cerr << "Model property invalid: " << error << "\n";
    return false;
  }
  return true;
}

// The sphere widget's placement as its VTK representation has it.
void SpherePlacement(vtkSMProxy* widget, double center[3], double& radius)
{
  widget->UpdatePropertyInformation();
  vtkSMPropertyHelper(widget, "CenterInfo").Get(center, 3);
  radius = vtkSMPropertyHelper(widget, "RadiusInfo").GetAsDouble();
}

// A world point in the view's display coordinates.
void ToDisplay(vtkRenderer* renderer, double x, double y, double z, int display[2])
{
  renderer->SetWorldPoint(x, y, z, 1.0);
  renderer->WorldToDisplay();
  const double* d = renderer->GetDisplayPoint();
  display[0] = static_cast<int>(std::lround(d[0]));
  display[1] = static_cast<int>(std::lround(d[1]));
}
}

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestPiEditorWidgetGUI <PiSurfaces plugin .so> <picture folder>\n";
    return EXIT_FAILURE;
  }
  const std::string plugin = argv[1];
  TestApplication<> application(argv[0]);
  pqApplicationCore& core = application.Application;
  pqObjectBuilder* builder = core.getObjectBuilder();
  pqServer* server = StartSession(builder, plugin);
  if (!server)
  {
    return EXIT_FAILURE;
  }

  // A window with the properties panel on the left and a render view on the right.
  QWidget window;
  auto* layout = new QHBoxLayout(&window);
  pqRenderView* view = CreateRenderView(builder, server);
  if (!view)
  {
    return EXIT_FAILURE;
  }
  vtkSMProxy* viewProxy = view->getProxy();
  pqPipelineSource* source = builder->createSource("sources", "PiSurface", server);
  vtkSMProxy* proxy = source->getProxy();
  vtkSMPropertyHelper(proxy, "Resolution").Set(48);
  proxy->UpdateVTKObjects();
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  auto* sourceProxy = vtkSMSourceProxy::SafeDownCast(proxy);
  controller->Show(sourceProxy, 0, vtkSMViewProxy::SafeDownCast(viewProxy));
  controller->Show(sourceProxy, 1, vtkSMViewProxy::SafeDownCast(viewProxy));

  auto* panel = new pqProxyWidget(proxy, &window);
  panel->setApplyChangesImmediately(false);
  panel->setView(view);
  panel->setMinimumWidth(440);
  layout->addWidget(panel);
  layout->addWidget(view->widget(), 1);
  window.resize(1200, 860);
  window.show();
  CHECK(QTest::qWaitForWindowExposed(&window), "the window is shown");
  view->resetCamera();
  view->forceRender();
  QPointer<pqRenderView> liveView = view;
  auto apply = [&]()
  {
    panel->apply();
    proxy->UpdateVTKObjects();
    if (liveView)
    {
      liveView->forceRender();
    }
  };

  auto* table = Find<QTableWidget>(panel, "PiPrimitiveTable");
  auto* showWidget = Find<QCheckBox>(panel, "PiShowWidget");
  if (!table || !showWidget)
  {
    return EXIT_FAILURE;
  }
  CHECK(showWidget->isChecked(), "the 3D widget is on by default");

  // Row 0 (the sphere at x = 0.9, radius 1) gets a visible sphere widget.
  table->selectRow(0);
  vtkSMNewWidgetRepresentationProxy* sphere = FindWidget(viewProxy, "SphereWidgetRepresentation");
  CHECK(sphere && Shown(sphere), "a visible sphere widget in the view");
  CHECK(CountWidgets(viewProxy) == 1, "one widget, not " << CountWidgets(viewProxy));
  if (!sphere)
  {
    return EXIT_FAILURE;
  }
  CHECK(sphere->GetWidget() && sphere->GetWidget()->GetEnabled(),
    "the VTK sphere widget is enabled in the view's interactor");
  double center[3];
  double radius = 0;
  SpherePlacement(sphere, center, radius);
  CHECK(Near3(center, 0.9, 0, 0) && Near(radius, 1),
    "the widget is row 0's sphere: centre " << Str3(center) << ", radius " << radius);

  // The widget moves (its proxy set, then the interaction events of its VTK widget, as a
  // drag fires them): the row's fields follow at once, the Model on Apply.
  const std::string before = ModelText(proxy);
  const double moved[3] = { 0.5, 0.25, -0.125 };
  vtkSMPropertyHelper(sphere, "Center").Set(moved, 3);
  vtkSMPropertyHelper(sphere, "Radius").Set(0.75);
  sphere->UpdateVTKObjects();
  sphere->GetWidget()->InvokeEvent(vtkCommand::StartInteractionEvent);
  sphere->GetWidget()->InvokeEvent(vtkCommand::InteractionEvent);
  CHECK(Find<QLineEdit>(panel, "PiParameter_Center_0")->text() == "0.5" &&
      Find<QLineEdit>(panel, "PiParameter_Center_1")->text() == "0.25",
    "the centre fields follow during the drag");
  sphere->GetWidget()->InvokeEvent(vtkCommand::EndInteractionEvent);
  const QString radiusText = Find<QLineEdit>(panel, "PiParameter_Radius")->text();
  CHECK(radiusText == "0.75", "the radius field follows: " << radiusText.toStdString());
  CHECK(ModelText(proxy) == before, "the Model waits for Apply");
  apply();
  pisurf::Model model;
  CHECK(Parse(proxy, model) && model.Primitives.size() == 2 &&
      Near3(model.Primitives[0].Center, 0.5, 0.25, -0.125) &&
      Near(model.Primitives[0].Radius, 0.75) && Near3(model.Primitives[1].Center, -0.9, 0, 0),
    "the Model has the moved sphere: " << ModelText(proxy));
  CHECK(
    ModelText(proxy).find("\"radius\": 0.75") != std::string::npos, "the JSON says radius 0.75");
  CHECK(FindWidget(viewProxy, "SphereWidgetRepresentation") == sphere && Shown(sphere),
    "the same widget stays after Apply");

  // A typed radius and centre move the widget.
  Type(Find<QLineEdit>(panel, "PiParameter_Radius"), "1.25");
  Type(Find<QLineEdit>(panel, "PiParameter_Center_0"), "1");
  SpherePlacement(sphere, center, radius);
  CHECK(Near(radius, 1.25) && Near3(center, 1, 0.25, -0.125),
    "the widget follows the typed radius and centre: " << Str3(center) << ", " << radius);
  apply();

  // A real drag: press on the sphere's front, move right, release, through the view's
  // interactor. ParaView's sphere widget translates the sphere.
  view->resetCamera();
  view->forceRender();
  vtkSMRenderViewProxy* renderViewProxy = view->getRenderViewProxy();
  vtkRenderWindowInteractor* interactor = renderViewProxy->GetInteractor();
  vtkRenderer* renderer = renderViewProxy->GetRenderer();
  int from[2];
  int to[2];
  ToDisplay(renderer, 1, 0.25, -0.125, from);
  ToDisplay(renderer, 1.5, 0.25, -0.125, to);
  interactor->SetEventInformation(from[0], from[1]);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  for (int step = 1; step <= 5; ++step)
  {
    interactor->SetEventInformation(
      from[0] + (to[0] - from[0]) * step / 5, from[1] + (to[1] - from[1]) * step / 5);
    interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  }
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
  SpherePlacement(sphere, center, radius);
  std::cerr << "after the drag from " << from[0] << "," << from[1] << " to " << to[0] << ","
            << to[1] << ": centre " << Str3(center) << ", radius " << radius << "\n";
  apply();
  CHECK(Parse(proxy, model) && model.Primitives[0].Center[0] > 1.2 &&
      Near3(model.Primitives[0].Center, center[0], center[1], center[2], 1e-6) &&
      Near(model.Primitives[0].Radius, 1.25),
    "the drag moved the sphere to x = 1.5 in the Model: " << ModelText(proxy));

  // A real right-button drag upwards on the sphere scales it: the radius grows.
  const double dragged[3] = { center[0], center[1], center[2] };
  ToDisplay(renderer, dragged[0], dragged[1], dragged[2], from);
  interactor->SetEventInformation(from[0], from[1]);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  interactor->InvokeEvent(vtkCommand::RightButtonPressEvent);
  for (int step = 1; step <= 5; ++step)
  {
    interactor->SetEventInformation(from[0], from[1] + 12 * step);
    interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  }
  interactor->InvokeEvent(vtkCommand::RightButtonReleaseEvent);
  SpherePlacement(sphere, center, radius);
  std::cerr << "after the scaling drag: centre " << Str3(center) << ", radius " << radius << "\n";
  apply();
  CHECK(Parse(proxy, model) && model.Primitives[0].Radius > 1.3 &&
      Near(model.Primitives[0].Radius, radius, 1e-6) &&
      Near3(model.Primitives[0].Center, dragged[0], dragged[1], dragged[2], 1e-6),
    "the right-button drag grew the radius, the centre stays: " << ModelText(proxy));

  // Another row: the widget moves to it.
  table->selectRow(1);
  SpherePlacement(sphere, center, radius);
  CHECK(Near3(center, -0.9, 0, 0) && Near(radius, 1), "row 1's sphere: " << Str3(center));

  // An ellipsoid gets a box: Position the centre, Scale the semi-axes.
  auto* rowType = Find<QComboBox>(panel, "PiPrimitiveTypeRow1");
  rowType->setCurrentIndex(rowType->findText("Ellipsoid"));
  Type(Find<QLineEdit>(panel, "PiParameter_Radii_0"), "1.5");
  vtkSMNewWidgetRepresentationProxy* box = FindWidget(viewProxy, "BoxWidgetRepresentation");
  CHECK(box && Shown(box) && CountWidgets(viewProxy) == 1,
    "an ellipsoid has a box widget, and only that: " << CountWidgets(viewProxy) << " widgets");
  if (box)
  {
    double position[3];
    double scale[3];
    box->UpdatePropertyInformation();
    vtkSMPropertyHelper(box, "PositionInfo").Get(position, 3);
    vtkSMPropertyHelper(box, "ScaleInfo").Get(scale, 3);
    CHECK(Near3(position, -0.9, 0, 0, 1e-6) && Near3(scale, 1.5, 1, 1, 1e-6),
      "the box is the ellipsoid's: position " << Str3(position) << ", scale " << Str3(scale));
    // Scaling the box edits the semi-axes.
    const double scaled[3] = { 1.5, 0.5, 2 };
    vtkSMPropertyHelper(box, "Scale").Set(scaled, 3);
    box->UpdateVTKObjects();
    box->GetWidget()->InvokeEvent(vtkCommand::StartInteractionEvent);
    box->GetWidget()->InvokeEvent(vtkCommand::EndInteractionEvent);
    apply();
    CHECK(Parse(proxy, model) && model.Primitives[1].Type == pisurf::PrimitiveType::Ellipsoid &&
        Near3(model.Primitives[1].Radii, 1.5, 0.5, 2, 1e-6),
      "the box's scale is the ellipsoid's semi-axes: " << ModelText(proxy));
    // The untouched centre keeps its typed value exactly (no round-off from the box).
    CHECK(Near3(model.Primitives[1].Center, -0.9, 0, 0, 0),
      "the centre stays -0.9 exactly: " << ModelText(proxy));
    CHECK(model.Primitives[1].Orient == pisurf::Orientation::Default,
      "an unturned box leaves the orientation alone: " << ModelText(proxy));

    // Turning the box turns the ellipsoid: 30 degrees about z (Rotation is the widget's
    // Euler angles, vtkProp3D's Rz Rx Ry).
    const double turned[3] = { 0, 0, 30 };
    vtkSMPropertyHelper(box, "Rotation").Set(turned, 3);
    box->UpdateVTKObjects();
    box->GetWidget()->InvokeEvent(vtkCommand::StartInteractionEvent);
    box->GetWidget()->InvokeEvent(vtkCommand::EndInteractionEvent);
    CHECK(Find<QComboBox>(panel, "PiParameter_Orientation")->currentIndex() == 2,
      "the orientation field says Rotation");
    apply();
    {
      const pisurf::PrimitiveSpec* e =
        Parse(proxy, model) && model.Primitives.size() == 2 ? &model.Primitives[1] : nullptr;
      CHECK(e && e->Orient == pisurf::Orientation::Rotation &&
          Near(e->RotationAngle * (e->RotationAxis[2] > 0 ? 1 : -1), 30, 1e-6) &&
          Near3(e->RotationAxis, 0, 0, e->RotationAxis[2] > 0 ? 1 : -1, 1e-9) &&
          Near3(e->Radii, 1.5, 0.5, 2, 1e-6) && Near3(e->Center, -0.9, 0, 0, 0),
        "the turned box is the ellipsoid rotated 30 degrees about z: " << ModelText(proxy));
    }
    // Typing a rotation turns the box: 90 degrees about x.
    Type(Find<QLineEdit>(panel, "PiParameter_RotationAxis_0"), "1");
    Type(Find<QLineEdit>(panel, "PiParameter_RotationAxis_2"), "0");
    Type(Find<QLineEdit>(panel, "PiParameter_RotationAngle"), "90");
    double euler[3];
    box->UpdatePropertyInformation();
    vtkSMPropertyHelper(box, "RotationInfo").Get(euler, 3);
    CHECK(Near3(euler, 90, 0, 0, 1e-6),
      "a typed rotation of 90 degrees about x turns the box: " << Str3(euler));
    apply();
  }
  // The picture for the user guide: the editor and the box widget on the ellipsoid, seen
  // from above the x-z plane.
  vtkCamera* camera = renderViewProxy->GetActiveCamera();
  camera->Azimuth(30);
  camera->Elevation(25);
  renderViewProxy->SynchronizeCameraProperties();
  view->resetCamera();
  camera->Zoom(0.85); // the box reaches beyond the data
  renderViewProxy->SynchronizeCameraProperties();
  view->forceRender();
  QCoreApplication::processEvents();
  window.grab().save(QString(argv[2]) + "/PiEditorWidget.png");

  // A torus gets a handle at its centre.
  rowType = Find<QComboBox>(panel, "PiPrimitiveTypeRow1");
  rowType->setCurrentIndex(rowType->findText("Torus"));
  vtkSMNewWidgetRepresentationProxy* handle = FindWidget(viewProxy, "HandleWidgetRepresentation");
  CHECK(handle && Shown(handle) && CountWidgets(viewProxy) == 1, "a torus has a handle");
  if (handle)
  {
    const double there[3] = { -1, 0.5, 0 };
    vtkSMPropertyHelper(handle, "WorldPosition").Set(there, 3);
    handle->UpdateVTKObjects();
    handle->GetWidget()->InvokeEvent(vtkCommand::EndInteractionEvent);
    apply();
    CHECK(Parse(proxy, model) && model.Primitives[1].Type == pisurf::PrimitiveType::Torus &&
        Near3(model.Primitives[1].Center, -1, 0.5, 0),
      "the handle moves the torus: " << ModelText(proxy));
  }

  // The checkbox hides and shows it; so does the panel.
  showWidget->setChecked(false);
  CHECK(handle && !Shown(handle), "unchecked: hidden");
  showWidget->setChecked(true);
  CHECK(handle && Shown(handle), "checked: shown again");
  panel->hide();
  CHECK(handle && !Shown(handle), "a hidden panel hides the widget");
  panel->show();
  CHECK(handle && Shown(handle), "a shown panel shows it again");

  // A change of the property from outside (Python, undo, a state file) moves the widget.
  vtkSMPropertyHelper(proxy, "Model").Set(R"({"pisurf": 1, "blending": 0.1,
            "primitives": [{"type": "sphere", "center": [2, 0, 0], "radius": 0.5}]})");
  proxy->UpdateVTKObjects();
  QCoreApplication::processEvents();
  sphere = FindWidget(viewProxy, "SphereWidgetRepresentation");
  CHECK(sphere && Shown(sphere) && CountWidgets(viewProxy) == 1,
    "the new model's sphere has the sphere widget");
  if (sphere)
  {
    SpherePlacement(sphere, center, radius);
    CHECK(Near3(center, 2, 0, 0) && Near(radius, 0.5),
      "the widget follows the property: " << Str3(center) << ", " << radius);
  }

  // The view goes: the widget leaves it, the editor keeps working.
  builder->destroy(view);
  QCoreApplication::processEvents();
  CHECK(!liveView, "the view is gone");
  Type(Find<QLineEdit>(panel, "PiParameter_Radius"), "0.75");
  apply();
  CHECK(Parse(proxy, model) && Near(model.Primitives[0].Radius, 0.75),
    "the editor works without a view: " << ModelText(proxy));

  // Another view gets the widget; a deleted editor (its source deleted, say) takes it out.
  auto* other = qobject_cast<pqRenderView*>(builder->createView("RenderView", server));
  panel->setView(other);
  sphere = FindWidget(other->getProxy(), "SphereWidgetRepresentation");
  CHECK(sphere && Shown(sphere) && CountWidgets(other->getProxy()) == 1,
    "the new view gets the sphere widget");
  window.hide();
  delete panel;
  CHECK(CountWidgets(other->getProxy()) == 0, "a deleted editor leaves no widget in the view");
  builder->destroy(other);
  builder->destroy(source);
  builder->removeServer(server);
  std::cerr << (Failures ? "FAILED" : "passed") << " (" << Failures << " failures)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
