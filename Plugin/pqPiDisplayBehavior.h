// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class pqPiDisplayBehavior
 * @brief the paper's default look for Pi-surfaces shown in a render view of the GUI
 *
 * An auto-start part of the PiSurfaces plugin. When the GUI creates a representation
 * in a render view (the first Show of that port in that view), it gives it the look of
 * the paper's figures:
 * - "Pi Surface", "Pi Surface Model Reader", "Pi Product": the Π-surface (port 0) solid
 *   grey and translucent (Opacity DefaultOpacity) over the Primitives port (port 1)
 *   coloured by `Factor` as categories, one palette colour per primitive; when the
 *   Π-surface lies inside its primitives (F negative far away in most directions, as
 *   with a negated factor digging a dent) the Π-surface is opaque and the primitives
 *   translucent, so that the result stays in front. An empty Primitives port (Pi
 *   Product without GeneratePrimitives) is hidden and not coloured.
 * - "Pi Primitive": the next colour of the palette.
 * - Molecules ("Pi Molecule Reader", "Molecular Pi Surface"): the `AtomicNumber` colour
 *   map becomes categorical with CPK colours (H white, C grey, N blue, O red, ...).
 * A Primitives port is computed on the server only for a visible consumer
 * (vtkPiSIOnDemandSourceProxy): its producer is updated when its representation is
 * created or shown again, so that the colouring and the Information panel see its
 * data.
 * It also names the VTK object of each PiSurfaces source and filter after its proxy
 * (vtkObject::SetObjectName), so that error messages say which source refused a value.
 *
 * It only touches newly created representations: nothing while a state file is
 * loaded (vtkSMSessionProxyManager::GetInLoadXMLState) or while undo/redo re-creates
 * proxies, so saved states restore what the user saved, and the user may change
 * everything afterwards. It lives in the Qt client: pvpython and pvbatch `Show()` keep
 * ParaView's defaults.
 *
 * @warning It reacts to pqServerManagerModel::representationAdded, which ParaView
 * emits while vtkSMParaViewPipelineControllerWithRendering::Show registers the new
 * representation, after the representation's defaults (ColorArrayName) are chosen.
 */
#ifndef pqPiDisplayBehavior_h
#define pqPiDisplayBehavior_h

#include <QObject>

class pqPipelineSource;
class pqRepresentation;
class vtkSMProxy;

class pqPiDisplayBehavior : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqPiDisplayBehavior(QObject* parent = nullptr);
  ~pqPiDisplayBehavior() override;

  /// The opacity of the Π-surface (0.35) and its grey (0.75 0.75 0.75).
  static constexpr double DefaultOpacity = 0.35;
  static constexpr double DefaultGrey = 0.75;

  /// Auto-start interface: connect to / disconnect from the server manager model.
  void startup();
  void shutdown();

  /// Gives `representation` (a render-view representation) the Pi-surface look if
  /// its input is port 0 or 1 of one of the Pi-surface proxies; false if it is not one.
  static bool ApplyDefaults(vtkSMProxy* representation);

protected Q_SLOTS:
  void onRepresentationAdded(pqRepresentation* representation);
  /// Names the VTK object of a PiSurfaces source or filter after its proxy (built-in
  /// session), so that its error messages say which source refused a value.
  void onSourceNamed(pqPipelineSource* source);

private:
  Q_DISABLE_COPY(pqPiDisplayBehavior)
};

#endif
