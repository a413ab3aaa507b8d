// SPDX-License-Identifier: BSD-3-Clause
// GUI test of the primitive editor (pqPiPrimitiveListWidget) under Xvfb. Debian's
// ParaView has no PythonQt, so a `paraview --script` cannot reach Qt widgets: this is a
// small ParaView client instead. It loads the PiSurfaces plugin like the GUI does (its
// XML and its Qt interfaces), creates a "Pi Surface", builds the source's real
// properties panel (pqProxyWidget), finds the editor's controls by object name and
// drives them with QTest: add a torus, edit its minor radius, an invalid radius and an
// odd superellipsoid exponent (both refused), duplicate / move / remove, and a change of
// the property from outside. After each Apply it checks the Model JSON and the mesh.
#include "PiModel.h"
#include "PiQtTestUtilities.h"

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqPipelineSource.h"
#include "pqProxyWidget.h"
#include "pqServer.h"
#include "pqServerResource.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPluginManager.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSourceProxy.h"

#include <QCheckBox>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
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

void Bounds(vtkSMProxy* proxy, double b[6])
{
  auto* source = vtkSMSourceProxy::SafeDownCast(proxy);
  source->UpdatePipeline();
  source->GetDataInformation(0)->GetBounds(b);
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestPiPrimitiveEditorGUI <PiSurfaces plugin .so> [picture folder]\n";
    return EXIT_FAILURE;
  }
  // argv[2], optional: a folder for a picture of the editor.
  const std::string plugin = argv[1];
  TestApplication<> application(argv[0]);
  pqApplicationCore& core = application.Application;
  vtkNew<OutputRecorder> recorder; // a refused edit reaches the output window
  vtkOutputWindow::SetInstance(recorder);

  pqObjectBuilder* builder = core.getObjectBuilder();
  pqServer* server = StartSession(builder, plugin);
  if (!server)
  {
    return EXIT_FAILURE;
  }
  pqPipelineSource* source = builder->createSource("sources", "PiSurface", server);
  vtkSMProxy* proxy = source->getProxy();
  vtkSMPropertyHelper(proxy, "Resolution").Set(48);
  proxy->UpdateVTKObjects();
  double before[6];
  Bounds(proxy, before);

  // The source's properties panel, as the Properties dock builds it.
  pqProxyWidget panel(proxy);
  panel.setApplyChangesImmediately(false);
  panel.resize(460, 1100);
  panel.show();
  CHECK(QTest::qWaitForWindowExposed(&panel), "the panel is shown");
  auto apply = [&]()
  {
    panel.apply();
    proxy->UpdateVTKObjects();
  };

  auto* table = Find<QTableWidget>(&panel, "PiPrimitiveTable");
  if (!table)
  {
    std::cerr << "the Model property did not get the primitive editor\n";
    return EXIT_FAILURE;
  }
  CHECK(
    table->rowCount() == 2, "the default model has 2 primitives, the table " << table->rowCount());

  // Add a torus: choose the type, click Add.
  auto* newType = Find<QComboBox>(&panel, "PiNewPrimitiveType");
  newType->setCurrentIndex(newType->findText("Torus"));
  QTest::mouseClick(Find<QPushButton>(&panel, "PiAddPrimitive"), Qt::LeftButton);
  CHECK(table->rowCount() == 3, "a third row after Add");
  CHECK(table->currentRow() == 2 || table->selectionModel()->isRowSelected(2, QModelIndex()),
    "the new row is selected");
  apply();
  pisurf::Model model;
  CHECK(Parse(proxy, model) && model.Primitives.size() == 3 &&
      model.Primitives[2].Type == pisurf::PrimitiveType::Torus &&
      model.Primitives[2].MinorRadius == 0.25,
    "the Model has the torus with the default minor radius");
  CHECK(ModelText(proxy) == pisurf::WriteModel(model), "the Model JSON is canonical");

  // Edit its minor radius.
  Type(Find<QLineEdit>(&panel, "PiParameter_MinorRadius"), "0.4");
  apply();
  CHECK(Parse(proxy, model) && model.Primitives.size() == 3 &&
      model.Primitives[2].MinorRadius == 0.4 && model.Primitives[2].MajorRadius == 1.0,
    "minor_radius 0.4 in the Model: " << ModelText(proxy));
  CHECK(ModelText(proxy).find("\"minor_radius\": 0.4") != std::string::npos,
    "the JSON text says minor_radius 0.4");
  double after[6];
  Bounds(proxy, after);
  std::cerr << "y max: " << before[3] << " before, " << after[3] << " with the torus\n";
  // The two spheres reach y = 1 (a little more blended); the torus's tube y = 1 + 0.4.
  CHECK(after[3] > 1.4 && after[3] < 1.5 && after[3] > before[3] + 0.1,
    "the mesh reaches the torus's outer equator y = 1.4, not " << after[3]);

  // An invalid minor radius is refused: red field, message, warning, model unchanged.
  const std::string valid = ModelText(proxy);
  recorder->Text.clear();
  auto* minor = Find<QLineEdit>(&panel, "PiParameter_MinorRadius");
  Type(minor, "-0.1");
  apply();
  CHECK(ModelText(proxy) == valid, "a negative minor radius leaves the Model unchanged");
  CHECK(minor->styleSheet().contains("background"), "the refused field is marked");
  auto* status = Find<QLabel>(&panel, "PiStatus");
  CHECK(status && status->isVisible() && status->text().contains("minor_radius"),
    "the status names the parameter: " << (status ? status->text().toStdString() : ""));
  CHECK(recorder->Text.find("minor_radius") != std::string::npos,
    "the refusal is a warning in the output window");
  CHECK(
    std::string(Find<QLineEdit>(&panel, "PiParameter_MajorRadius")->text().toStdString()) == "1",
    "the other fields still show the model");

  if (argc > 2)
  {
    // A picture of the editor with the refused field, for the user guide.
    QCoreApplication::processEvents();
    panel.grab().save(QString(argv[2]) + "/PiPrimitiveEditor.png");
  }

  // A superellipsoid with an odd exponent is refused too (the core's rule).
  auto* rowType = Find<QComboBox>(&panel, "PiPrimitiveTypeRow2");
  rowType->setCurrentIndex(rowType->findText("Superellipsoid"));
  apply();
  CHECK(Parse(proxy, model) && model.Primitives[2].Type == pisurf::PrimitiveType::Superellipsoid,
    "the row's type selector changes the type");
  const std::string superellipsoid = ModelText(proxy);
  Type(Find<QLineEdit>(&panel, "PiParameter_Exponent"), "3");
  apply();
  CHECK(ModelText(proxy) == superellipsoid, "an odd exponent leaves the Model unchanged");
  Type(Find<QLineEdit>(&panel, "PiParameter_Exponent"), "6");
  apply();
  CHECK(Parse(proxy, model) && model.Primitives[2].Exponent == 6, "an even exponent is taken");
  CHECK(!status->isVisible(), "the message goes once an edit is accepted");

  // Negate and scale.
  Find<QCheckBox>(&panel, "PiParameter_Negate")->click();
  Type(Find<QLineEdit>(&panel, "PiParameter_Scale"), "2");
  apply();
  CHECK(Parse(proxy, model) && model.Primitives[2].Negate && model.Primitives[2].Scale == 2,
    "negate and scale reach the Model");

  // Duplicate, move up, remove.
  QTest::mouseClick(Find<QPushButton>(&panel, "PiDuplicatePrimitive"), Qt::LeftButton);
  CHECK(table->rowCount() == 4, "Duplicate adds a row");
  Find<QLineEdit>(&panel, "PiParameter_Center_0");
  Type(Find<QLineEdit>(&panel, "PiParameter_Center_0"), "3");
  QTest::mouseClick(Find<QPushButton>(&panel, "PiMovePrimitiveUp"), Qt::LeftButton);
  apply();
  CHECK(Parse(proxy, model) && model.Primitives.size() == 4 && model.Primitives[2].Center[0] == 3 &&
      model.Primitives[3].Center[0] == 0,
    "the moved copy is third: " << ModelText(proxy));
  QTest::mouseClick(Find<QPushButton>(&panel, "PiRemovePrimitive"), Qt::LeftButton);
  apply();
  CHECK(Parse(proxy, model) && model.Primitives.size() == 3 && model.Primitives[2].Center[0] == 0,
    "Remove drops the selected row");

  // The blending r.
  Type(Find<QLineEdit>(&panel, "PiBlending"), "0.5");
  apply();
  CHECK(Parse(proxy, model) && model.Blending == 0.5, "r = 0.5 in the Model");

  // A change of the property from outside (Python, undo, a state file) refreshes it.
  vtkSMPropertyHelper(proxy, "Model")
    .Set(R"({"pisurf": 1, "blending": 0.1, "bounds": [-1, 1, -1, 1, -1, 1],
            "primitives": [{"type": "cone", "angle": 20}]})");
  proxy->UpdateVTKObjects();
  QCoreApplication::processEvents();
  CHECK(table->rowCount() == 1, "the table follows the property: " << table->rowCount() << " rows");
  CHECK(Find<QLineEdit>(&panel, "PiParameter_Angle") &&
      Find<QLineEdit>(&panel, "PiParameter_Angle")->text() == "20",
    "the selected row shows the new cone");
  CHECK(Find<QLineEdit>(&panel, "PiBlending")->text() == "0.1", "r follows the property");
  CHECK(!status->isVisible(), "a valid property shows no message");
  // An invalid text from outside is reported; the table keeps the last valid model.
  vtkSMPropertyHelper(proxy, "Model").Set(R"({"pisurf": 1, "blending": 0.1, "primitives": []})");
  proxy->UpdateVTKObjects();
  QCoreApplication::processEvents();
  CHECK(status->isVisible() && table->rowCount() == 1, "an invalid property is reported");
  vtkSMPropertyHelper(proxy, "Model")
    .Set(R"({"pisurf": 1, "blending": 0.1, "bounds": [-1, 1, -1, 1, -1, 1],
            "primitives": [{"type": "cone", "angle": 20}]})");
  proxy->UpdateVTKObjects();
  QCoreApplication::processEvents();

  // Removing the last primitive is refused (a model needs one).
  QTest::mouseClick(Find<QPushButton>(&panel, "PiRemovePrimitive"), Qt::LeftButton);
  CHECK(table->rowCount() == 1, "the last primitive stays");

  panel.hide();
  builder->destroy(source);
  builder->removeServer(server);
  std::cerr << (Failures ? "FAILED" : "passed") << " (" << Failures << " failures)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
