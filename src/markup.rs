//! The one writer of SVG pictures and HTML pages.
//!
//! Every picture and page rasterlab writes (grid pictures, the check
//! report's counterexample and page, the `compare` report, the bench
//! chart, the legends) is written through a [`Markup`]: an element is
//! opened with its attributes, text goes in, the element is closed. Every
//! attribute value and every text is escaped by the one [`escape`]
//! (`& < > " '`), so a caption, a file name or a program's message can
//! hold any character without breaking the picture.
//!
//! It is deliberately small: names of elements and attributes are the
//! code's own constants and are written as given; there is no tree, no
//! checking that elements close in order (the pictures are written in
//! one pass, and the tests parse them). Markup already written by a
//! [`Markup`] (a legend, a picture placed into a page), a style sheet or a
//! script goes in whole with [`Markup::raw`].
//!
//! The example below runs as this module's unit test
//! `the_example_writes_an_escaped_picture` (the module is private to the
//! crate, so it cannot run as a documentation test):
//!
//! ```text
//! let mut m = Markup::new();
//! m.open("svg", &[("width", &20), ("height", &10)]);
//! m.element("text", &[("x", &2.5), ("class", &"caption")], "a < b & \"c\"");
//! m.empty("rect", &[("width", &20), ("fill", &"#009e73")]);
//! m.close("svg");
//! assert_eq!(
//!     m.finish(),
//!     "<svg width=\"20\" height=\"10\"><text x=\"2.5\" class=\"caption\">a &lt; b &amp; &quot;c&quot;</text><rect width=\"20\" fill=\"#009e73\"/></svg>"
//! );
//! ```

use std::fmt::{Display, Write};

/// An attribute: its name and its value (anything that prints; escaped
/// when written).
pub(crate) type Attr<'a> = (&'a str, &'a dyn Display);

/// Text made safe for XML and HTML, in text and in attribute values:
/// `&`, `<`, `>`, `"` and `'` become entities.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// SVG or HTML being written, element by element.
#[derive(Debug, Default)]
pub(crate) struct Markup {
    out: String,
}

impl Markup {
    /// Nothing written yet.
    pub(crate) fn new() -> Markup {
        Markup::default()
    }

    /// `<name` and the attributes, each value escaped.
    fn start(&mut self, name: &str, attrs: &[Attr]) {
        self.out.push('<');
        self.out.push_str(name);
        for (key, value) in attrs {
            let value = value.to_string();
            let _ = write!(self.out, " {key}=\"{}\"", escape(&value));
        }
    }

    /// Opens element `name` with `attrs`: `<name a="v">`.
    pub(crate) fn open(&mut self, name: &str, attrs: &[Attr]) -> &mut Markup {
        self.start(name, attrs);
        self.out.push('>');
        self
    }

    /// Opens an `<svg>` picture `width` by `height` user units, its
    /// viewBox the same, in DejaVu Sans at `font_size` px (`None`: left
    /// to the elements).
    pub(crate) fn open_svg(
        &mut self,
        width: f64,
        height: f64,
        font_size: Option<u32>,
    ) -> &mut Markup {
        let view_box = format!("0 0 {width} {height}");
        let mut attrs: Vec<Attr> = vec![
            ("xmlns", &"http://www.w3.org/2000/svg"),
            ("width", &width),
            ("height", &height),
            ("viewBox", &view_box),
            ("font-family", &"DejaVu Sans, sans-serif"),
        ];
        if let Some(size) = &font_size {
            attrs.push(("font-size", size));
        }
        self.open("svg", &attrs)
    }

    /// Closes element `name`: `</name>`.
    pub(crate) fn close(&mut self, name: &str) -> &mut Markup {
        let _ = write!(self.out, "</{name}>");
        self
    }

    /// An element without content: `<name a="v"/>` (also right for
    /// HTML's void elements, `<img>`, `<meta>`, `<br>`).
    pub(crate) fn empty(&mut self, name: &str, attrs: &[Attr]) -> &mut Markup {
        self.start(name, attrs);
        self.out.push_str("/>");
        self
    }

    /// An element holding `text`, escaped: `<name a="v">text</name>`.
    pub(crate) fn element(&mut self, name: &str, attrs: &[Attr], text: &str) -> &mut Markup {
        self.open(name, attrs);
        self.text(text);
        self.close(name)
    }

    /// Text, escaped.
    pub(crate) fn text(&mut self, text: &str) -> &mut Markup {
        self.out.push_str(&escape(text));
        self
    }

    /// Markup written elsewhere by a [`Markup`] (a legend, a picture), or
    /// a style sheet or script of the code's own, as it is.
    pub(crate) fn raw(&mut self, markup: &str) -> &mut Markup {
        self.out.push_str(markup);
        self
    }

    /// A name on a picture: bold 14 px text centred at `(x, y)`, in
    /// `colour` on a white halo (a stroke painted under the fill), so it
    /// reads over cells and edges alike.
    pub(crate) fn halo_label(
        &mut self,
        class: &str,
        (x, y): (f64, f64),
        colour: &str,
        text: &str,
    ) -> &mut Markup {
        self.element(
            "text",
            &[
                ("class", &class),
                ("x", &format_args!("{x:.1}")),
                ("y", &format_args!("{y:.1}")),
                ("font-size", &14),
                ("font-weight", &"bold"),
                ("text-anchor", &"middle"),
                ("fill", &colour),
                ("stroke", &"white"),
                ("stroke-width", &3),
                ("paint-order", &"stroke"),
            ],
            text,
        )
    }

    /// A line break, to keep long pictures readable as text.
    pub(crate) fn newline(&mut self) -> &mut Markup {
        self.out.push('\n');
        self
    }

    /// What was written.
    pub(crate) fn finish(self) -> String {
        self.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_example_writes_an_escaped_picture() {
        let mut m = Markup::new();
        m.open("svg", &[("width", &20), ("height", &10)]);
        m.element(
            "text",
            &[("x", &2.5), ("class", &"caption")],
            "a < b & \"c\"",
        );
        m.empty("rect", &[("width", &20), ("fill", &"#009e73")]);
        m.close("svg");
        assert_eq!(
            m.finish(),
            "<svg width=\"20\" height=\"10\"><text x=\"2.5\" class=\"caption\">a &lt; b &amp; &quot;c&quot;</text><rect width=\"20\" fill=\"#009e73\"/></svg>"
        );
    }

    #[test]
    fn every_special_character_is_escaped_in_text_and_attributes() {
        let nasty = "<&>\"' é";
        assert_eq!(escape(nasty), "&lt;&amp;&gt;&quot;&#39; é");
        let mut m = Markup::new();
        m.element("title", &[("data-x", &nasty)], nasty);
        let svg = m.finish();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let title = doc.root_element();
        assert_eq!(title.attribute("data-x"), Some(nasty));
        assert_eq!(title.text(), Some(nasty));
    }
}
