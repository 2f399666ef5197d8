//! The subjects drawing the cases: the caller's one, or a pool of one per
//! job drawing a batch of cases in parallel; and the maker of those
//! subjects for a request (a built-in back-end, or an outside program).

use super::mode::Mode;
use crate::check::case::Case;
use crate::check::program::Program;
use crate::check::property::Property;
use crate::check::request::{CheckRequest, Kind, SubjectSpec};
use crate::check::{polygon_fragments, Builtin, Fragment, Subject, SubjectError};
use crate::error::{Error, Result};
use crate::raster::edge::FillRule;
use crate::raster::polygon::WindingRule;
use crate::raster::registry::{polygon_backend, Backend};

/// The subjects drawing the cases: the caller's one, or a pool of one per
/// job.
pub(crate) enum Subjects<'s> {
    /// One subject, drawing every case in turn.
    One(&'s mut dyn Subject),
    /// One subject per worker thread.
    Pool(Vec<Box<dyn Subject + Send>>),
}

impl Subjects<'_> {
    /// The subject that shrinks and confirms.
    pub(super) fn first(&mut self) -> &mut dyn Subject {
        match self {
            Subjects::One(s) => &mut **s,
            Subjects::Pool(v) => v[0].as_mut(),
        }
    }

    /// How many cases are worth drawing at once.
    pub(super) fn batch(&self) -> u32 {
        match self {
            Subjects::One(_) => 1,
            Subjects::Pool(v) => (v.len() * 4).max(8) as u32,
        }
    }

    /// Draws the cases, the pool's subjects in parallel; the results in
    /// the order of the cases.
    pub(super) fn draw_all(
        &mut self,
        cases: &[(u32, Case)],
    ) -> Vec<std::result::Result<Vec<Fragment>, SubjectError>> {
        let subjects = match self {
            Subjects::One(s) => return draw_until_broken(&mut **s, cases),
            Subjects::Pool(v) if v.len() == 1 => return draw_until_broken(v[0].as_mut(), cases),
            Subjects::Pool(v) => v,
        };
        let next = std::sync::atomic::AtomicUsize::new(0);
        let mut results: Vec<Option<std::result::Result<Vec<Fragment>, SubjectError>>> =
            (0..cases.len()).map(|_| None).collect();
        let slots = std::sync::Mutex::new(&mut results);
        std::thread::scope(|scope| {
            for subject in subjects.iter_mut() {
                let (next, slots) = (&next, &slots);
                scope.spawn(move || loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some((_, case)) = cases.get(k) else {
                        break;
                    };
                    let r = subject.draw(case);
                    if let Ok(mut s) = slots.lock() {
                        s[k] = Some(r);
                    }
                });
            }
        });
        results
            .into_iter()
            .map(|r| r.unwrap_or_else(|| Err(SubjectError::Start("a worker stopped".into()))))
            .collect()
    }
}

/// The cases drawn one after another, up to the first that breaks the
/// subject (the engine stops there: a program that hangs is not made to
/// hang on the rest of the batch too).
fn draw_until_broken(
    subject: &mut dyn Subject,
    cases: &[(u32, Case)],
) -> Vec<std::result::Result<Vec<Fragment>, SubjectError>> {
    let mut out = Vec::with_capacity(cases.len());
    for (_, case) in cases {
        let result = subject.draw(case);
        let broken = result.is_err();
        out.push(result);
        if broken {
            break;
        }
    }
    out
}

/// One subject per worker.
pub(super) type Factory<'a> = Box<dyn Fn() -> Box<dyn Subject + Send> + Sync + 'a>;

/// The subject's name in the report, and a maker of subjects.
pub(super) fn subject_factory<'a>(
    request: &'a CheckRequest,
    chosen: Option<Backend>,
    kind: Kind,
    mode: Mode,
) -> Result<(String, Factory<'a>)> {
    let rule = match mode {
        Mode::One(Property::Exact(rule)) => rule,
        _ => FillRule::TopLeft,
    };
    Ok(match (chosen, &request.subject) {
        (Some(Backend::Triangle(b)), SubjectSpec::Backend(name)) if kind == Kind::Triangles => (
            format!("backend {name}"),
            Box::new(move || Box::new(Builtin::triangles(b, rule)) as Box<dyn Subject + Send>),
        ),
        (Some(Backend::Line(b)), SubjectSpec::Backend(name)) if kind == Kind::Lines => {
            let pixel_index = matches!(mode, Mode::One(Property::Line(c)) if c.whole_pixels());
            (
                format!("backend {name}"),
                Box::new(move || {
                    if pixel_index {
                        // Pixel indices name pixels: the segment runs
                        // between their centres.
                        Box::new(
                            move |c: &Case| -> std::result::Result<Vec<Fragment>, SubjectError> {
                                let mut centred = c.clone();
                                for l in &mut centred.lines {
                                    *l = l.map(|p| (p.0.round() + 0.5, p.1.round() + 0.5));
                                }
                                Builtin::Lines(b).draw(&centred)
                            },
                        ) as Box<dyn Subject + Send>
                    } else {
                        Box::new(Builtin::Lines(b)) as Box<dyn Subject + Send>
                    }
                }),
            )
        }
        (None, SubjectSpec::Backend(name)) if kind == Kind::Polygons => {
            let b = polygon_backend(name)?;
            let fill = match mode {
                Mode::One(Property::Polygon(fill)) => fill,
                _ => WindingRule::default(),
            };
            (
                format!("backend {name}"),
                Box::new(move || {
                    Box::new(
                        move |c: &Case| -> std::result::Result<Vec<Fragment>, SubjectError> {
                            Ok(polygon_fragments(b, c, fill))
                        },
                    ) as Box<dyn Subject + Send>
                }),
            )
        }
        (_, SubjectSpec::Backend(name)) => {
            return Err(Error::InvalidArgument(format!(
                "back-end `{name}` does not draw {}",
                match kind {
                    Kind::Lines => "lines",
                    Kind::Triangles => "triangles",
                    Kind::Polygons => "polygons",
                }
            )))
        }
        (_, SubjectSpec::Exec(command) | SubjectSpec::Persistent(command)) => {
            let word = match mode {
                Mode::One(Property::Exact(rule)) => rule.name(),
                Mode::One(Property::Watertight) => "watertight",
                Mode::One(Property::CrackFree) => "crack-free",
                Mode::One(Property::Line(c)) => c.name(),
                Mode::One(Property::Polygon(fill)) => fill.name(),
                Mode::AnyRule | Mode::AnyConvention => "any",
            };
            let mut program = if matches!(request.subject, SubjectSpec::Persistent(_)) {
                Program::persistent(command, word)?
            } else {
                Program::new(command, word)
            };
            program.timeout = request.timeout;
            (
                command.clone(),
                Box::new(move || Box::new(program.clone()) as Box<dyn Subject + Send>),
            )
        }
    })
}

/// A subject whose y grows up from the bottom of the target
/// ([`Origin::BottomLeft`](crate::check::request::Origin)): given each
/// case with `y` turned into `height - y`, its rows turned back from
/// `height - 1 - row`. Both are exact (a whole number minus a multiple of
/// 1/512, and snapping to even is symmetric about a whole number), so the
/// subject is judged on the very case it was given; a vertex near the
/// guard band's edge may, measured up, lie up to `height` px past it.
pub(super) struct YUp(pub(super) Box<dyn Subject + Send>);

impl Subject for YUp {
    fn draw(&mut self, case: &Case) -> std::result::Result<Vec<Fragment>, SubjectError> {
        let last = i64::from(case.height) - 1;
        Ok(self
            .0
            .draw(&case.flipped_y())?
            .into_iter()
            .map(|f| Fragment { y: last - f.y, ..f })
            .collect())
    }
}
