//! What a widget can ask for ([`Command`]), which handler takes it ([`Group`]) and
//! whether it makes an undo step ([`UndoKey`]): each command is classified once, here.

use crate::contours::BroadPhaseKind;
use crate::evolution::{ForceWeights, Modality, Mode, Polarity, Shape};
use crate::geometry::Point;
use crate::io::export::Format;
use std::path::PathBuf;

/// What a click on the canvas does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Tool {
    /// Click for a seed disk, drag to set its radius.
    Seed,
    /// Drag a rectangle.
    Rect,
    /// Click polygon corners; double-click (or click the first corner) to close.
    Polygon,
    /// Select, drag or delete seeds and shapes.
    Select,
    /// Edit the contours by hand: drag a vertex (through the topology core), click to
    /// select a contour, Delete removes it.
    Edit,
    /// Push contours with a disc: from inside a region its boundary moves out, from
    /// outside it moves in (merges, splits and holes happen exactly).
    Brush,
    /// Paint training strokes (background, object, boundary) for the pixel classifier.
    Train,
}

/// Everything a widget can ask for; applied in one place, [`super::TopoApp::apply`].
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Open the image at a path.
    OpenImage(PathBuf),
    /// Open a file dialog and then the chosen image.
    OpenDialog,
    /// Add a shape to the initialisation.
    AddShape(Shape),
    /// Move shape `index` by a vector.
    MoveShape {
        /// The shape.
        index: usize,
        /// By how much, in image pixels.
        by: Point,
    },
    /// Delete shape `index`.
    DeleteShape(usize),
    /// Select a shape (or none).
    Select(Option<usize>),
    /// Choose the canvas tool.
    SetTool(Tool),
    /// Add a wrap rectangle this many pixels inside the border.
    WrapBorder(f64),
    /// Place one seed per object found in the image (automatic seeds), as editable shapes.
    FindSeeds,
    /// The kind of image (phase contrast treats the halo as background).
    SetModality(Modality),
    /// Whether the adaptive engine opens holes in clear background inside a region.
    SetOpenHoles(bool),
    /// Play the evolution.
    Play,
    /// Pause playback.
    Pause,
    /// Step this many frames.
    Step(usize),
    /// Step until a frame with a topology event (or convergence).
    StepToEvent,
    /// Throw the run away (undoable) and show the initialisation.
    Reset,
    /// Show recorded frame `n` (0: the initialisation).
    SeekFrame(usize),
    /// Write the frame on screen to a file.
    Export(Format, PathBuf),
    /// Choose a file in a dialog, then export.
    ExportDialog(Format),
    /// Objects darker or brighter than the background.
    SetPolarity(Polarity),
    /// The engine.
    SetMode(Mode),
    /// The broad phase of the crossing search.
    SetBroadPhase(BroadPhaseKind),
    /// Run a second engine beside the first, on the same image and shapes (or stop).
    SetCompare(Option<Mode>),
    /// New force weights and step: a run goes on from the frame on screen with them.
    SetForces {
        /// The weights.
        weights: ForceWeights,
        /// The step, in grid spacings.
        step: f64,
    },
    /// Segment every image of a folder with the shapes and parameters on screen, in the
    /// background; outputs go to its `topocontour` subfolder.
    ApplyToFolder(PathBuf),
    /// Choose the folder in a dialog, then apply to it.
    ApplyToFolderDialog,
    /// Stop the folder run after the image in progress.
    CancelFolder,
    /// Show page `n` (0-based) of a multi-page image; shapes stay.
    SetPage(usize),
    /// The physical size of a pixel (none: unknown).
    SetPixelSize(Option<crate::io::PixelSize>),
    /// The smallest region or hole exported, square pixels.
    SetMinArea(f64),
    /// The contrast window (low, high) of the image on screen.
    SetContrast((f32, f32)),
    /// Put the force weights, step, minimum area and contrast back to their defaults.
    ResetParameters,
    /// Save the image reference, shapes, parameters and the frame on screen as a session.
    SaveSession(PathBuf),
    /// Open a session: its image, shapes and parameters, run to its frame.
    OpenSession(PathBuf),
    /// Choose a file in a dialog, then save (true) or open (false) a session there.
    SessionDialog(bool),
    /// Hand edit: move contour vertex `vertex` of the frame on screen to `to`, through the
    /// topology core (merges, splits and holes happen exactly, logged as events).
    HandMove {
        /// The vertex (of the frame on screen).
        vertex: u32,
        /// Where to, in image pixels.
        to: Point,
        /// Which drag (press) this is part of: each drag is one undo step, whichever
        /// vertex leads it.
        stroke: u32,
    },
    /// Hand edit begins: the contour vertex of the frame on screen nearest to `at` within
    /// `tol` is grabbed (the drag's `HandMove`s move it).
    GrabVertex {
        /// Where the press was, in image pixels.
        at: Point,
        /// How far a vertex may be, in image pixels.
        tol: f64,
    },
    /// Hand edit: a brush stroke of `radius` from `from` to `to` on the frame on screen.
    Brush {
        /// Where the brush's centre was.
        from: Point,
        /// Where it is now.
        to: Point,
        /// The brush's radius, pixels.
        radius: f64,
        /// Which stroke (press) this is part of: each stroke is one undo step.
        stroke: u32,
    },
    /// Hand edit: delete the contour `id` of the frame on screen (with its holes).
    DeleteContour(u32),
    /// Select a contour of the frame on screen to see its measurements (or none).
    SelectContour(Option<u32>),
    /// Undo the last change of the document (Ctrl+Z).
    Undo,
    /// Redo what Undo undid (Ctrl+Shift+Z, Ctrl+Y).
    Redo,
    /// Open a movie: a multi-page TIFF or a folder of frames.
    OpenMovie(PathBuf),
    /// Choose a movie in a dialog (a folder when true, else a TIFF), then open it.
    OpenMovieDialog(bool),
    /// Show frame `n` of the movie (0-based; the evolution's run starts again).
    SeekMovieFrame(usize),
    /// Play the movie's frames one after another, or pause them (Space on a tracked movie).
    PlayMovie(bool),
    /// Track the movie from frame 0 in the background.
    Track,
    /// Track from frame 0 even though it replaces the corrections made by hand.
    TrackConfirmed,
    /// Track on from the last frame tracked.
    ContinueTrack,
    /// Put the correction of tracked frame `n` into the tracking and track the frames
    /// after it again, even though that replaces later corrections.
    Retrack(usize),
    /// Close the question on screen.
    CloseQuestion,
    /// Stop tracking after the frame in progress (the frames tracked are kept).
    CancelTrack,
    /// Select a track (its outline is highlighted, its row in the lineage view).
    SelectTrack(Option<u32>),
    /// Paint a training stroke of `label` (0 erases) from `from` to `to`.
    Paint {
        /// Where the brush's centre was.
        from: Point,
        /// Where it is now.
        to: Point,
        /// 1 background, 2 object, 3 boundary, 0 erase.
        label: u8,
        /// The brush's radius, pixels.
        radius: f64,
        /// Which stroke (press) this is part of: each stroke is one undo step.
        stroke: u32,
    },
    /// The label the Train tool paints (keys 0–3).
    SetTrainLabel(u8),
    /// Show the probability map over the image (or not).
    ShowProbabilities(bool),
    /// Wipe every training stroke.
    ClearStrokes,
    /// Write the classifier trained on the strokes to a file.
    SaveClassifier(PathBuf),
    /// Read a classifier file: it applies while no strokes are painted.
    LoadClassifier(PathBuf),
    /// Choose a classifier file in a dialog, then save (true) or load (false) it.
    ClassifierDialog(bool),
    /// Write the tracking result in the Cell Tracking Challenge layout to a folder.
    ExportCtc(PathBuf),
    /// Choose the folder in a dialog, then export the tracking result.
    ExportCtcDialog,
}

/// The handler a command goes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// Hand edits of the frame on screen.
    Hand,
    /// Undo and redo.
    History,
    /// The user's shapes.
    Shapes,
    /// Playing, stepping, seeking.
    Playback,
    /// The tool and the run's parameters.
    Parameters,
    /// Images, exports, sessions, folders.
    Files,
    /// Movies and tracking.
    Movie,
    /// Training strokes and classifiers.
    Train,
}

/// How a command joins the undo history.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UndoKey {
    /// A change of the document that is a step of its own.
    Step,
    /// Part of a gesture: consecutive commands of the same gesture are one step.
    Gesture(Gesture),
}

/// A gesture that sends one command per frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gesture {
    /// A drag of shape `n` with the Select tool.
    MoveShape(usize),
    /// A hand drag or brush stroke (one press), by its id.
    Stroke(u32),
    /// A drag of the force sliders.
    Forces,
    /// A drag of the pixel size.
    PixelSize,
    /// A drag of the minimum area.
    MinArea,
    /// A drag of a contrast slider.
    Contrast,
}

impl Command {
    /// The handler this command goes to.
    pub fn group(&self) -> Group {
        use Command::*;
        match self {
            HandMove { .. }
            | Brush { .. }
            | GrabVertex { .. }
            | DeleteContour(..)
            | SelectContour(..) => Group::Hand,
            Undo | Redo => Group::History,
            AddShape(..)
            | MoveShape { .. }
            | DeleteShape(..)
            | Select(..)
            | WrapBorder(..)
            | FindSeeds => Group::Shapes,
            Play | Pause | Step(..) | StepToEvent | Reset | SeekFrame(..) => Group::Playback,
            SetTool(..)
            | SetModality(..)
            | SetOpenHoles(..)
            | SetPolarity(..)
            | SetMode(..)
            | SetCompare(..)
            | SetBroadPhase(..)
            | SetForces { .. }
            | SetPage(..)
            | SetPixelSize(..)
            | SetMinArea(..)
            | SetContrast(..)
            | ResetParameters => Group::Parameters,
            OpenImage(..) | OpenDialog | Export(..) | ExportDialog(..) | SessionDialog(..)
            | SaveSession(..) | OpenSession(..) | ApplyToFolder(..) | ApplyToFolderDialog
            | CancelFolder => Group::Files,
            OpenMovie(..) | OpenMovieDialog(..) | SeekMovieFrame(..) | PlayMovie(..) | Track
            | TrackConfirmed | ContinueTrack | Retrack(..) | CloseQuestion | CancelTrack
            | SelectTrack(..) | ExportCtc(..) | ExportCtcDialog => Group::Movie,
            Paint { .. }
            | SetTrainLabel(..)
            | ShowProbabilities(..)
            | ClearStrokes
            | SaveClassifier(..)
            | LoadClassifier(..)
            | ClassifierDialog(..) => Group::Train,
        }
    }

    /// Whether this command changes the document, and so joins the undo history (none:
    /// playing, stepping, selecting, exporting and dialogs are not undone).
    pub fn undo_key(&self) -> Option<UndoKey> {
        use Command::*;
        let gesture = |g| Some(UndoKey::Gesture(g));
        match *self {
            MoveShape { index, .. } => gesture(Gesture::MoveShape(index)),
            HandMove { stroke, .. } | Brush { stroke, .. } | Paint { stroke, .. } => {
                gesture(Gesture::Stroke(stroke))
            }
            SetForces { .. } => gesture(Gesture::Forces),
            SetPixelSize(_) => gesture(Gesture::PixelSize),
            SetMinArea(_) => gesture(Gesture::MinArea),
            SetContrast(_) => gesture(Gesture::Contrast),
            OpenImage(_) | OpenSession(_) | AddShape(_) | DeleteShape(_) | WrapBorder(_)
            | FindSeeds | SetPolarity(_) | SetModality(_) | SetOpenHoles(_) | SetMode(_)
            | SetBroadPhase(_) | SetCompare(_) | Reset | ResetParameters | SetPage(_)
            | DeleteContour(_) | OpenMovie(_) | ClearStrokes | LoadClassifier(_) => {
                Some(UndoKey::Step)
            }
            GrabVertex { .. }
            | SelectContour(_)
            | Undo
            | Redo
            | Select(_)
            | SetTool(_)
            | Play
            | Pause
            | Step(_)
            | StepToEvent
            | SeekFrame(_)
            | Export(..)
            | OpenDialog
            | ExportDialog(_)
            | SessionDialog(_)
            | SaveSession(_)
            | ApplyToFolder(_)
            | ApplyToFolderDialog
            | CancelFolder
            | OpenMovieDialog(_)
            | SeekMovieFrame(_)
            | PlayMovie(_)
            | Track
            | TrackConfirmed
            | ContinueTrack
            | Retrack(_)
            | CloseQuestion
            | CancelTrack
            | SelectTrack(_)
            | ExportCtc(_)
            | ExportCtcDialog
            | SetTrainLabel(_)
            | ShowProbabilities(_)
            | SaveClassifier(_)
            | ClassifierDialog(_) => None,
        }
    }
}
