// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiQtTestUtilities.h
 * @brief what the QTest ParaView clients of Testing/Qt share
 *
 * A failure counter with its CHECK macro, the Qt and ParaView applications, a builtin
 * session with the plugin loaded,
 * widgets found by object name, typing into a field, the Pi Surface's Model text, near
 * comparisons, ParaView's interactive widgets found in a view, and a recorder of what
 * reaches the output window.
 * Each test is its own program: everything here is per translation unit.
 */
#ifndef PiQtTestUtilities_h
#define PiQtTestUtilities_h

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerResource.h"
#include "vtkAbstractWidget.h"
#include "vtkCommand.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkSMNewWidgetRepresentationProxy.h"
#include "vtkSMPluginManager.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyManager.h"

#include <QApplication>
#include <QCoreApplication>
#include <QLineEdit>
#include <QTest>
#include <QWidget>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
int Failures = 0;

#define CHECK(condition, message)                                                                  \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << "FAILED line " << __LINE__ << ": " << message << "\n";                          \
      ++Failures;                                                                                  \
    }                                                                                              \
  } while (false)

// The Qt application and ParaView's application core (Core: pqApplicationCore or a
// subclass), given the program name only (they want argv[argc] == nullptr, and the
// test's own arguments are not theirs).
template <class Core = pqApplicationCore>
struct TestApplication
{
  int Argc = 1;
  char* Argv[2];
  QApplication App;
  Core Application;
  explicit TestApplication(char* program)
    : Argv{ program, nullptr }
    , App(Argc, Argv)
    , Application(Argc, Argv)
  {
  }
};

// Records what reaches ParaView's output window (warnings, errors), one message a line,
// and echoes it to the terminal. Install with vtkOutputWindow::SetInstance.
class OutputRecorder : public vtkOutputWindow
{
public:
  static OutputRecorder* New();
  vtkTypeMacro(OutputRecorder, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    this->Text += text ? text : "";
    this->Text += "\n";
    std::cerr << (text ? text : "") << "\n";
  }
  std::string Text;
};
vtkStandardNewMacro(OutputRecorder);

// A builtin session with the plugin (its .so) loaded; null, with a message, if either fails.
inline pqServer* StartSession(pqObjectBuilder* builder, const std::string& plugin)
{
  pqServer* server = builder->createServer(pqServerResource("builtin:"));
  if (!server ||
    !vtkSMProxyManager::GetProxyManager()->GetPluginManager()->LoadLocalPlugin(plugin.c_str()))
  {
    std::cerr << "cannot start a session or load " << plugin << "\n";
    return nullptr;
  }
  return server;
}

// A render view on the session; null, with a message, if it cannot be made.
inline pqRenderView* CreateRenderView(pqObjectBuilder* builder, pqServer* server)
{
  auto* view = qobject_cast<pqRenderView*>(builder->createView("RenderView", server));
  if (!view)
  {
    std::cerr << "no render view\n";
  }
  return view;
}

template <class T>
T* Find(QWidget* root, const char* name)
{
  // Deleted parameter panels wait for the event loop: flush them first.
  QCoreApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);
  auto* w = root->findChild<T*>(name);
  if (!w)
  {
    std::cerr << "FAILED: no widget named " << name << "\n";
    ++Failures;
  }
  return w;
}

inline void Type(QLineEdit* edit, const char* text)
{
  edit->setFocus();
  edit->selectAll();
  QTest::keyClicks(edit, text);
  QTest::keyClick(edit, Qt::Key_Return);
}

inline std::string ModelText(vtkSMProxy* proxy)
{
  return vtkSMPropertyHelper(proxy, "Model").GetAsString();
}

inline bool Near(double a, double b, double tolerance = 1e-9)
{
  return std::abs(a - b) <= tolerance;
}

inline bool Near3(const double a[3], double x, double y, double z, double tolerance = 1e-9)
{
  return Near(a[0], x, tolerance) && Near(a[1], y, tolerance) && Near(a[2], z, tolerance);
}

inline std::string Str3(const double v[3])
{
  return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
    ")";
}

inline bool Shown(vtkSMProxy* widget)
{
  return widget && vtkSMPropertyHelper(widget, "Visibility").GetAsInt() == 1 &&
    vtkSMPropertyHelper(widget, "Enabled").GetAsInt() == 1;
}

// The interactive widgets in the view (only the shown ones, when `shownOnly`): ParaView
// keeps them in HiddenRepresentations.
inline int CountWidgets(vtkSMProxy* view, bool shownOnly = false)
{
  int count = 0;
  vtkSMPropertyHelper hidden(view, "HiddenRepresentations");
  for (unsigned int i = 0; i < hidden.GetNumberOfElements(); ++i)
  {
    auto* widget = vtkSMNewWidgetRepresentationProxy::SafeDownCast(hidden.GetAsProxy(i));
    if (widget && (!shownOnly || Shown(widget)))
    {
      ++count;
    }
  }
  return count;
}

// The view's widget of that XML name (the shown one, when `shownOnly`: a panel may hold
// several of a kind, one per type, hidden but the current type's).
inline vtkSMNewWidgetRepresentationProxy* FindWidget(
  vtkSMProxy* view, const char* xmlName, bool shownOnly = false)
{
  vtkSMPropertyHelper hidden(view, "HiddenRepresentations");
  for (unsigned int i = 0; i < hidden.GetNumberOfElements(); ++i)
  {
    auto* widget = vtkSMNewWidgetRepresentationProxy::SafeDownCast(hidden.GetAsProxy(i));
    if (widget && std::string(widget->GetXMLName()) == xmlName && (!shownOnly || Shown(widget)))
    {
      return widget;
    }
  }
  return nullptr;
}

// A drag of `widget` after its placement was set: the events its VTK widget fires.
inline void Drag(vtkSMNewWidgetRepresentationProxy* widget)
{
  widget->UpdateVTKObjects();
  widget->GetWidget()->InvokeEvent(vtkCommand::StartInteractionEvent);
  widget->GetWidget()->InvokeEvent(vtkCommand::InteractionEvent);
  widget->GetWidget()->InvokeEvent(vtkCommand::EndInteractionEvent);
}

}

#endif
