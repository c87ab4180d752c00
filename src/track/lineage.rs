//! The lineage: one record per track (label, first and last frame, parent), as the Cell
//! Tracking Challenge's `res_track.txt` lists them (`L B E P`, one line per track).

/// One track: a cell from the frame it appeared (or was born) to the frame it was last
/// seen (or divided after).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Track {
    /// The track's label (1, 2, …), also its value in the label images.
    pub label: u32,
    /// First frame (0-based).
    pub first: usize,
    /// Last frame.
    pub last: usize,
    /// The track it divided from (0: none).
    pub parent: u32,
}

/// A division: `parent`'s last frame was `frame − 1`, its two children start at `frame`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Division {
    /// The first frame of the children.
    pub frame: usize,
    /// The track that divided.
    pub parent: u32,
    /// The two children.
    pub children: [u32; 2],
}

impl Division {
    /// The division in words, as the event log shows it.
    pub fn describe(&self) -> String {
        format!(
            "cell {} divided into {} and {} at frame {}",
            self.parent, self.children[0], self.children[1], self.frame
        )
    }
}

/// The tracks of a movie so far, by label. Labels are given in order of birth and never
/// given again, so a withdrawn track leaves a gap; the frames tracked again after a
/// correction keep the numbers the run they replace gave ([`Lineage::start_at`]), and
/// their new tracks are numbered after that run's ([`Lineage::reserve`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Lineage {
    tracks: Vec<Track>,
    /// The last label given.
    given: u32,
}

impl Lineage {
    /// A new track starting at `frame`; returns its label.
    pub fn start(&mut self, frame: usize, parent: u32) -> u32 {
        self.given += 1;
        let label = self.given;
        self.tracks.push(Track {
            label,
            first: frame,
            last: frame,
            parent,
        });
        label
    }

    /// A new track starting at `frame` labelled `label`, which no track has; labels given
    /// on follow the largest given. Returns `label`.
    pub fn start_at(&mut self, label: u32, frame: usize, parent: u32) -> u32 {
        debug_assert!(self.index(label).is_none(), "track {label} exists");
        self.insert(Track {
            label,
            first: frame,
            last: frame,
            parent,
        });
        label
    }

    /// `track` as it is, unless a track has its label; labels given on follow the
    /// largest given.
    pub fn insert(&mut self, track: Track) {
        if self.index(track.label).is_some() {
            return;
        }
        let k = self.tracks.partition_point(|t| t.label < track.label);
        self.tracks.insert(k, track);
        self.given = self.given.max(track.label);
    }

    /// New labels follow `label` at least: the labels up to it stay free for
    /// [`Lineage::start_at`].
    pub fn reserve(&mut self, label: u32) {
        self.given = self.given.max(label);
    }

    /// The largest label given.
    pub fn last_label(&self) -> u32 {
        self.given
    }

    /// Track `label` is seen in `frame`.
    pub fn extend(&mut self, label: u32, frame: usize) {
        if let Some(k) = self.index(label) {
            let t = &mut self.tracks[k];
            t.last = t.last.max(frame);
        }
    }

    /// Takes back `division`: its children are no tracks, and its parent goes on to
    /// `frame` (sisters that came apart for a frame and were one cell again).
    pub fn undo(&mut self, division: &Division, frame: usize) {
        self.tracks
            .retain(|t| !division.children.contains(&t.label));
        self.extend(division.parent, frame);
    }

    /// Dates `division` at its frame, a frame earlier than it was found: its parent's
    /// last frame is the one before, its children start there.
    pub fn redate(&mut self, division: &Division) {
        for t in self.tracks.iter_mut() {
            if t.label == division.parent {
                t.last = division.frame.saturating_sub(1);
            } else if division.children.contains(&t.label) {
                t.first = division.frame;
            }
        }
    }

    /// The tracks that began before `frame`, as they were up to `frame − 1`; labels given
    /// later follow the largest kept.
    pub fn before(&self, frame: usize) -> Lineage {
        let tracks: Vec<Track> = self
            .tracks
            .iter()
            .filter(|t| t.first < frame)
            .map(|t| Track {
                last: t.last.min(frame.saturating_sub(1)),
                ..*t
            })
            .collect();
        let given = tracks.last().map_or(0, |t| t.label);
        Lineage { tracks, given }
    }

    /// The lineage of saved `tracks` (a session's), checked: labels from 1 in increasing
    /// order, each within `frames` frames tracked, a parent an earlier track (or 0).
    pub fn from_tracks(tracks: Vec<Track>, frames: usize) -> Result<Lineage, String> {
        let mut before = 0;
        for t in &tracks {
            if t.label <= before {
                return Err(format!("track {} is listed out of order", t.label));
            }
            if t.first > t.last || t.last >= frames {
                return Err(format!(
                    "track {} spans frames {} to {} of {frames} tracked",
                    t.label, t.first, t.last
                ));
            }
            let parent_known = t.parent == 0
                || tracks
                    .binary_search_by_key(&t.parent, |k| k.label)
                    .is_ok_and(|_| t.parent < t.label);
            if !parent_known {
                return Err(format!(
                    "track {} has no parent track {}",
                    t.label, t.parent
                ));
            }
            before = t.label;
        }
        Ok(Lineage {
            given: before,
            tracks,
        })
    }

    /// All tracks, by label.
    pub fn tracks(&self) -> &[Track] {
        &self.tracks
    }

    /// The track of `label`.
    pub fn get(&self, label: u32) -> Option<&Track> {
        self.tracks.get(self.index(label)?)
    }

    /// Where track `label` is in [`Lineage::tracks`] (sorted by label, with gaps).
    fn index(&self, label: u32) -> Option<usize> {
        self.tracks.binary_search_by_key(&label, |t| t.label).ok()
    }

    /// `res_track.txt` of the Cell Tracking Challenge: `L B E P` per track.
    pub fn ctc_text(&self) -> String {
        self.tracks
            .iter()
            .map(|t| format!("{} {} {} {}\n", t.label, t.first, t.last, t.parent))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ctc_lines_list_label_first_last_parent() {
        let mut l = Lineage::default();
        let a = l.start(0, 0);
        l.extend(a, 4);
        let b = l.start(5, a);
        let c = l.start(5, a);
        l.extend(b, 9);
        assert_eq!(l.ctc_text(), "1 0 4 0\n2 5 9 1\n3 5 5 1\n");
        assert_eq!(l.get(c).unwrap().parent, 1);
    }

    #[test]
    fn a_division_taken_back_leaves_a_gap_no_label_fills() {
        let mut l = Lineage::default();
        let a = l.start(0, 0);
        let d = Division {
            frame: 3,
            parent: a,
            children: [l.start(3, a), l.start(3, a)],
        };
        let other = l.start(3, 0);
        l.undo(&d, 4);
        assert_eq!(l.ctc_text(), "1 0 4 0\n4 3 3 0\n");
        assert_eq!(l.get(2), None);
        assert_eq!(l.get(other).unwrap().first, 3);
        assert_eq!(l.start(5, 0), 5);
        // Before frame 4: the tracks begun by then, cut at frame 3; new labels follow.
        let mut b = l.before(4);
        assert_eq!(b.ctc_text(), "1 0 3 0\n4 3 3 0\n");
        assert_eq!(b.start(4, 0), 5);
    }
}
