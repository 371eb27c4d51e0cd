//! The figure report (`examples/thesis_report.rs`) in its quick mode: every
//! figure is written, is well-formed XML with drawn data, and is linked
//! from `index.html`.

#[allow(dead_code)]
#[path = "../examples/thesis_report.rs"]
mod thesis_report;

use std::path::Path;

/// A minimal XML well-formedness check: tags nest and close in order,
/// attributes are quoted, comments / declarations / CDATA are skipped.
/// Returns the names of the elements seen.
fn parse_xml(text: &str) -> Result<Vec<String>, String> {
    let b = text.as_bytes();
    let mut stack: Vec<String> = Vec::new();
    let mut seen = Vec::new();
    let mut i = 0;
    let mut roots = 0;
    while i < b.len() {
        if b[i] != b'<' {
            if stack.is_empty() && !b[i].is_ascii_whitespace() {
                return Err(format!("text outside the root element at byte {i}"));
            }
            i += 1;
            continue;
        }
        let rest = &text[i..];
        let skip = |open: &str, close: &str| -> Option<usize> {
            rest.starts_with(open)
                .then(|| rest.find(close).map(|e| e + close.len()))
                .flatten()
        };
        if rest.starts_with("<?") || rest.starts_with("<!--") || rest.starts_with("<![CDATA[") {
            let n = skip("<?", "?>")
                .or_else(|| skip("<!--", "-->"))
                .or_else(|| skip("<![CDATA[", "]]>"))
                .ok_or(format!("unterminated markup at byte {i}"))?;
            i += n;
            continue;
        }
        if rest.starts_with("<!") {
            i += rest.find('>').ok_or("unterminated declaration")? + 1;
            continue;
        }
        // A tag: find its end, honouring quotes.
        let mut j = i + 1;
        let mut quote = None;
        while j < b.len() {
            match (quote, b[j]) {
                (None, b'"') | (None, b'\'') => quote = Some(b[j]),
                (Some(q), c) if c == q => quote = None,
                (None, b'>') => break,
                (None, b'<') => return Err(format!("'<' inside a tag at byte {j}")),
                _ => {}
            }
            j += 1;
        }
        if j >= b.len() {
            return Err(format!("unterminated tag at byte {i}"));
        }
        let tag = &text[i + 1..j];
        if let Some(name) = tag.strip_prefix('/') {
            let name = name.trim();
            match stack.pop() {
                Some(open) if open == name => {}
                other => return Err(format!("</{name}> closes {other:?}")),
            }
        } else {
            let self_closing = tag.ends_with('/');
            let name: String = tag
                .chars()
                .take_while(|c| !c.is_whitespace() && *c != '/')
                .collect();
            if name.is_empty() || !name.chars().next().unwrap().is_alphabetic() {
                return Err(format!("bad element name in <{tag}>"));
            }
            if stack.is_empty() {
                roots += 1;
            }
            seen.push(name.clone());
            if !self_closing {
                stack.push(name);
            }
        }
        i = j + 1;
    }
    if !stack.is_empty() {
        return Err(format!("unclosed elements {stack:?}"));
    }
    if roots != 1 {
        return Err(format!("{roots} root elements"));
    }
    Ok(seen)
}

#[test]
fn xml_checker_rejects_malformed_documents() {
    assert!(parse_xml("<svg><path d=\"M0 0\"/></svg>").is_ok());
    assert!(parse_xml("<svg><g></svg>").is_err());
    assert!(parse_xml("<svg><g></g>").is_err());
    assert!(parse_xml("<svg a=\"1></svg>").is_err());
    assert!(parse_xml("<svg/><svg/>").is_err());
}

/// Does a `points="…"` or `d="…"` attribute carry at least two numbers?
fn has_drawn_data(svg: &str) -> bool {
    ["points=\"", " d=\""].iter().any(|key| {
        svg.match_indices(key).any(|(at, _)| {
            let v = &svg[at + key.len()..];
            let v = &v[..v.find('"').unwrap_or(0)];
            v.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
                .filter(|t| t.parse::<f64>().is_ok())
                .count()
                >= 4
        })
    })
}

#[test]
fn quick_report_writes_linked_well_formed_figures() {
    let dir = std::env::temp_dir().join(format!("mrr-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let figures = thesis_report::run(&thesis_report::Options {
        quick: true,
        out: dir.clone(),
    })
    .expect("report runs");
    let listed: usize = thesis_report::CHAPTERS.iter().map(|c| c.1.len()).sum();
    assert_eq!(figures.len(), listed);
    // The figures the report promises (thesis numbering).
    for id in [
        "fig2_11", "fig2_12", "fig2_18", "fig2_19", "fig2_20", "fig2_22", "fig3_1", "fig3_2",
        "fig3_3", "fig3_6", "fig3_7", "fig3_8", "fig4_3", "fig4_11", "fig5_7", "fig5_8", "fig5_10",
        "fig5_11", "fig6_10", "fig6_11", "fig6_14", "fig6_15", "fig6_16", "fig6_17", "fig6_19",
        "fig6_20",
    ] {
        assert!(
            figures
                .iter()
                .any(|f| f.file.starts_with(&format!("{id}_"))),
            "{id} missing"
        );
    }
    let index = std::fs::read_to_string(dir.join("index.html")).expect("index.html");
    parse_xml(&index[index.find("<html").expect("html element")..])
        .expect("index.html is well formed");
    for f in &figures {
        let path: &Path = &dir.join(&f.file);
        let svg = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", f.file));
        let names = parse_xml(&svg).unwrap_or_else(|e| panic!("{}: {e}", f.file));
        assert_eq!(names.first().map(String::as_str), Some("svg"), "{}", f.file);
        assert!(has_drawn_data(&svg), "{}: no drawn data", f.file);
        assert!(
            index.contains(&format!("src=\"{}\"", f.file)),
            "{} not linked from index.html",
            f.file
        );
        assert!(!f.ours.is_empty() && !f.thesis.is_empty(), "{}", f.file);
        assert!(!f.ours.contains("NaN"), "{}: {}", f.file, f.ours);
    }
    // The Markdown summary lists every figure with both columns filled.
    let summary = std::fs::read_to_string(dir.join("summary.md")).expect("summary.md");
    for f in &figures {
        let row = summary
            .lines()
            .find(|l| l.starts_with(&format!("| {} |", thesis_report::md_cell(&f.title))))
            .unwrap_or_else(|| panic!("{} missing from summary.md", f.title));
        assert_eq!(row.matches(" | ").count(), 2, "{row}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
