//! DICOM RT Structure Set (RTSTRUCT) input, read with the dicom-rs crates.
//!
//! What is read: the Structure Set ROI Sequence (3006,0020) for each ROI's number and name, and the
//! ROI Contour Sequence (3006,0039): per ROI (Referenced ROI Number, 3006,0084) its Contour Sequence
//! (3006,0040) of contours with Contour Geometric Type (3006,0042) `CLOSED_PLANAR` and Contour Data
//! (3006,0050, x y z triples in patient coordinates, mm). Contours of other types (`POINT`,
//! `OPEN_PLANAR`, `OPEN_NONPLANAR`: markers and lines) are skipped with a warning.
//!
//! Each ROI is one label: its ROI Number. Its name is kept in `Sections::label_names` (and so in the
//! reconstruction report), and `roi` selects ROIs by name. RTSTRUCT has no plane equations and no
//! holes: `io::loose_contours` fits the planes and finds the holes by nesting; the result is
//! validated and repaired like CSL and JSON input.
//!
//! Locations in messages: `FILE: ROI "NAME" (number N), contour K` with K the 0-based item of that
//! ROI's Contour Sequence; errors in the file's structure name the sequence items, e.g.
//! `FILE: ROIContourSequence[1].ContourSequence[3]`.
use super::loose_contours::{sections_from_loose_contours, LooseContour};
use crate::error::{Error, Result};
use crate::sections::Sections;
use crate::validate::{check_coordinate, ReadOptions};
use dicom_dictionary_std::tags;
use dicom_object::file::ReadPreamble;
use dicom_object::mem::InMemElement;
use dicom_object::{InMemDicomObject, OpenFileOptions, Tag};
use std::collections::BTreeMap;
use std::path::Path;

/// The contours of an RT Structure Set, by ROI, as read (nothing fitted or validated yet).
#[derive(Clone, Debug)]
pub struct RtStruct {
    /// The file, as named in messages.
    pub file: String,
    /// In the order of the ROI Contour Sequence.
    pub rois: Vec<Roi>,
    /// Skipped contours and ROIs without contours.
    pub warnings: Vec<String>,
}

/// One ROI: its number (the label), name and closed planar contours.
#[derive(Clone, Debug)]
pub struct Roi {
    pub number: i32,
    pub name: String,
    /// (item index in the ROI's Contour Sequence, points).
    pub contours: Vec<(usize, Vec<[f64; 3]>)>,
}

/// Read an RT Structure Set with every ROI.
pub fn read_rtstruct(path: &Path) -> Result<Sections> {
    read_rtstruct_with(path, &ReadOptions::default(), None)
}

/// Read an RT Structure Set with `options`; `roi`: only the ROI of this name (every ROI if `None`).
pub fn read_rtstruct_with(
    path: &Path,
    options: &ReadOptions,
    roi: Option<&str>,
) -> Result<Sections> {
    RtStruct::open(path)?.sections(roi, options)
}

impl RtStruct {
    /// Read the file's ROIs and contours.
    pub fn open(path: &Path) -> Result<RtStruct> {
        let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
        RtStruct::parse(&bytes, &path.display().to_string())
    }

    /// Read a DICOM file's bytes (with or without the 128-byte preamble); `file` names it in messages.
    pub fn parse(bytes: &[u8], file: &str) -> Result<RtStruct> {
        let object = OpenFileOptions::new()
            .read_preamble(ReadPreamble::Auto)
            .from_reader(bytes)
            .map_err(|e| Error::input(file, format!("not a readable DICOM file: {e}")))?;
        RtStruct::from_object(&object, file)
    }

    /// The ROIs of a DICOM data set.
    pub fn from_object(object: &InMemDicomObject, file: &str) -> Result<RtStruct> {
        let at = |path: &str| format!("{file}: {path}");
        let names = roi_names(object, file)?;
        let Some(roi_contours) = sequence(object, tags::ROI_CONTOUR_SEQUENCE, &at(""))? else {
            let modality = element(object, tags::MODALITY)
                .and_then(|e| e.to_str().ok())
                .map(|m| format!(" (Modality {})", m.trim()))
                .unwrap_or_default();
            return Err(Error::input(
                file,
                format!("no ROI Contour Sequence (3006,0039): not an RT Structure Set with contours{modality}"),
            ));
        };
        let mut rt = RtStruct {
            file: file.to_string(),
            rois: Vec::new(),
            warnings: Vec::new(),
        };
        let mut skipped = BTreeMap::<String, Vec<String>>::new();
        for (i, item) in roi_contours.iter().enumerate() {
            let path = format!("ROIContourSequence[{i}]");
            let number =
                integer(item, tags::REFERENCED_ROI_NUMBER, &at(&path))?.ok_or_else(|| {
                    Error::input(at(&path), "missing Referenced ROI Number (3006,0084)")
                })?;
            let name = names
                .get(&number)
                .cloned()
                .unwrap_or_else(|| format!("ROI {number}"));
            let mut roi = Roi {
                number,
                name,
                contours: Vec::new(),
            };
            let items = sequence(item, tags::CONTOUR_SEQUENCE, &at(&path))?.unwrap_or(&[]);
            for (k, contour) in items.iter().enumerate() {
                let cpath = at(&format!("{path}.ContourSequence[{k}]"));
                let kind = element(contour, tags::CONTOUR_GEOMETRIC_TYPE)
                    .ok_or_else(|| {
                        Error::input(&cpath, "missing Contour Geometric Type (3006,0042)")
                    })?
                    .to_str()
                    .map_err(|e| Error::input(&cpath, format!("Contour Geometric Type: {e}")))?
                    .trim()
                    .to_string();
                if kind != "CLOSED_PLANAR" {
                    skipped
                        .entry(kind)
                        .or_default()
                        .push(rt.contour_location(&roi, k));
                    continue;
                }
                roi.contours.push((k, contour_points(contour, &cpath)?));
            }
            if roi.contours.is_empty() {
                rt.warnings.push(format!(
                    "{}: ROI \"{}\" (number {}) has no closed planar contour",
                    file, roi.name, roi.number
                ));
            }
            rt.rois.push(roi);
        }
        for (kind, places) in skipped {
            let more = places.len().saturating_sub(3);
            let first: Vec<&str> = places.iter().take(3).map(String::as_str).collect();
            rt.warnings.push(format!(
                "skipped {} contour(s) of type {kind} (only CLOSED_PLANAR contours bound a section): {}{}",
                places.len(),
                first.join("; "),
                if more > 0 { format!(" and {more} more") } else { String::new() }
            ));
        }
        Ok(rt)
    }

    fn contour_location(&self, roi: &Roi, k: usize) -> String {
        format!(
            "{}: ROI \"{}\" (number {}), contour {k}",
            self.file, roi.name, roi.number
        )
    }

    /// The ROI names by ROI number (the labels).
    pub fn label_names(&self) -> BTreeMap<i32, String> {
        self.rois
            .iter()
            .map(|r| (r.number, r.name.clone()))
            .collect()
    }

    /// Validated sections of every ROI, or of the ROI named `roi`. Selecting happens before
    /// validation, because ROIs of one structure set may overlap (an organ inside the body
    /// outline), which sections of different labels may not.
    pub fn sections(&self, roi: Option<&str>, options: &ReadOptions) -> Result<Sections> {
        let selected: Vec<&Roi> = match roi {
            None => self.rois.iter().collect(),
            Some(name) => vec![self.roi_named(name)?],
        };
        let contours: Vec<LooseContour> = selected
            .iter()
            .flat_map(|r| {
                r.contours.iter().map(|(k, points)| LooseContour {
                    label: r.number,
                    points: points.clone(),
                    location: self.contour_location(r, *k),
                })
            })
            .collect();
        let names = selected
            .iter()
            .map(|r| (r.number, r.name.clone()))
            .collect();
        sections_from_loose_contours(&contours, &self.file, names, self.warnings.clone(), options)
            .map_err(|e| match e {
                Error::Input { location, reason } if selected.len() > 1 && overlap(&reason) => {
                    Error::Input {
                        location,
                        reason: format!(
                            "{reason} (ROIs of a structure set may overlap, sections of different labels may not: reconstruct one ROI with --roi NAME)"
                        ),
                    }
                }
                e => e,
            })
    }

    fn roi_named(&self, name: &str) -> Result<&Roi> {
        let matching: Vec<&Roi> = self.rois.iter().filter(|r| r.name == name).collect();
        match matching[..] {
            [one] => Ok(one),
            [] => Err(Error::input(
                format!("{}: --roi {name:?}", self.file),
                format!(
                    "no ROI of this name (ROIs: {})",
                    self.rois
                        .iter()
                        .map(|r| format!("{:?} (number {})", r.name, r.number))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
            _ => Err(Error::input(
                format!("{}: --roi {name:?}", self.file),
                format!(
                    "{} ROIs have this name (numbers {}); names must pick one",
                    matching.len(),
                    matching
                        .iter()
                        .map(|r| r.number.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
        }
    }
}

/// Validation messages about contours of one plane meeting or nesting wrongly.
fn overlap(reason: &str) -> bool {
    reason.contains("cross") || reason.contains("inside the material")
}

/// ROI number → name, from the Structure Set ROI Sequence (absent: no names).
fn roi_names(object: &InMemDicomObject, file: &str) -> Result<BTreeMap<i32, String>> {
    let mut names = BTreeMap::new();
    let items = sequence(
        object,
        tags::STRUCTURE_SET_ROI_SEQUENCE,
        &format!("{file}: "),
    )?;
    for (i, item) in items.unwrap_or(&[]).iter().enumerate() {
        let at = format!("{file}: StructureSetROISequence[{i}]");
        let Some(number) = integer(item, tags::ROI_NUMBER, &at)? else {
            continue; // a name without a number names nothing
        };
        if let Some(name) = element(item, tags::ROI_NAME) {
            let name = name
                .to_str()
                .map_err(|e| Error::input(&at, format!("ROI Name (3006,0026): {e}")))?;
            names.insert(number, name.trim().to_string());
        }
    }
    Ok(names)
}

/// The x y z triples of a contour's Contour Data.
fn contour_points(contour: &InMemDicomObject, at: &str) -> Result<Vec<[f64; 3]>> {
    let data = element(contour, tags::CONTOUR_DATA)
        .ok_or_else(|| Error::input(at, "missing Contour Data (3006,0050)"))?
        .to_multi_float64()
        .map_err(|e| Error::input(at, format!("Contour Data (3006,0050): {e}")))?;
    if data.len() % 3 != 0 {
        return Err(Error::input(
            at,
            format!(
                "Contour Data has {} numbers, not a multiple of 3 (x y z per point)",
                data.len()
            ),
        ));
    }
    if let Some(n) = integer(contour, tags::NUMBER_OF_CONTOUR_POINTS, at)? {
        if usize::try_from(n).ok() != Some(data.len() / 3) {
            return Err(Error::input(
                at,
                format!(
                    "Number of Contour Points is {n} but Contour Data has {} points",
                    data.len() / 3
                ),
            ));
        }
    }
    data.chunks_exact(3)
        .enumerate()
        .map(|(i, p)| {
            let mut x = [0.0; 3];
            for k in 0..3 {
                x[k] = check_coordinate(p[k])
                    .map_err(|e| Error::input(at, format!("point {i}: {e}")))?;
            }
            Ok(x)
        })
        .collect()
}

fn element(object: &InMemDicomObject, tag: Tag) -> Option<&InMemElement> {
    object.element_opt(tag).ok().flatten()
}

/// The items of sequence `tag`, `None` when absent; an error when the element is not a sequence.
fn sequence<'a>(
    object: &'a InMemDicomObject,
    tag: Tag,
    at: &str,
) -> Result<Option<&'a [InMemDicomObject]>> {
    match element(object, tag) {
        None => Ok(None),
        Some(e) => e
            .items()
            .map(Some)
            .ok_or_else(|| Error::input(at, format!("element {tag} is not a sequence"))),
    }
}

/// An integer element (IS, a decimal string), `None` when absent or empty.
fn integer(object: &InMemDicomObject, tag: Tag, at: &str) -> Result<Option<i32>> {
    let Some(e) = element(object, tag) else {
        return Ok(None);
    };
    let text = e
        .to_str()
        .map_err(|err| Error::input(at, format!("element {tag}: {err}")))?;
    let text = text.trim();
    if text.is_empty() {
        return Ok(None);
    }
    text.parse::<i32>().map(Some).map_err(|_| {
        let shown: String = text.chars().take(40).collect();
        Error::input(
            at,
            format!("element {tag}: expected an integer, found {shown:?}"),
        )
    })
}
