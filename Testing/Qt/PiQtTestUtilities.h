// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiQtTestUtilities.h
 * @brief what the QTest ParaView clients of Testing/Qt share
 *
 * A failure counter with its CHECK macro, a builtin session with the plugin loaded,
 * widgets found by object name, typing into a field, and the Pi Surface's Model text.
 * Each test is its own program: everything here is per translation unit.
 */
#ifndef PiQtTestUtilities_h
#define PiQtTestUtilities_h

#include "pqObjectBuilder.h"
#include "pqServer.h"
#include "pqServerResource.h"
#include "vtkSMPluginManager.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyManager.h"

#include <QCoreApplication>
#include <QLineEdit>
#include <QTest>
#include <QWidget>

#include <iostream>
#include <string>

namespace
{
int Failures = 0;

#define CHECK(condition, message)                                                              \
  do                                                                                           \
  {                                                                                            \
    if (!(condition))                                                                          \
    {                                                                                          \
      std::cerr << "FAILED line " << __LINE__ << ": " << message << "\n";                      \
      ++Failures;                                                                              \
    }                                                                                          \
  } while (false)

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
}

#endif
