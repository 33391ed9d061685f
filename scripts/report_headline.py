"""The one headline of every report.md the tools write (calibrate, diagnose; campaign writes the
same shape from C++): the title, then one line with the verdict, whether the model describes the
data, and what data it came from, so that a reader of any report sees the answer first. Also the
table of what each input file gave (the JSON's inputs_read), which both reports carry."""


def fmt(value, digits=3):
    if value is None:
        return "n/a"
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def adequacy_words(adequacy):
    """ADEQUATE, NOT ADEQUATE (reasons) or not assessed (why)."""
    if adequacy is None or adequacy.get("adequate") is None:
        reasons = "; ".join((adequacy or {}).get("reasons", []))
        return "not assessed" + (f" ({reasons})" if reasons else "")
    return "ADEQUATE" if adequacy["adequate"] else "NOT ADEQUATE (" + "; ".join(adequacy["reasons"]) + ")"


def verdict_words(test):
    """The string-stability test's verdict with both p-values named by their hypothesis."""
    if not test or not test.get("verdict"):
        return "not tested"
    if test.get("tested") is False:  # the JSON's verdict is then "undecided", with its reason
        return "NOT TESTED (" + (test.get("reason") or "no reason given") + ")"
    return (f"{test['verdict'].upper()} (p (H0: stable) = {fmt(test.get('p_value_stable_rejected'))}, "
            f"p (H0: unstable) = {fmt(test.get('p_value_unstable_rejected'))})")


def headline(title, verdict, adequacy, data):
    """Markdown lines: '# title', a blank line, and the headline line."""
    return [f"# {title}", "",
            f"**Verdict:** {verdict} · **Model:** {adequacy_words(adequacy)} · **Data:** {data}", ""]


def inputs_read_lines(inputs_read):
    """Markdown lines: '## Data read' and a table of each input's rows (or messages), the samples
    used and every other count the reader gives that is not zero (docs/TOOLS.md names them)."""
    if not inputs_read:
        return []
    lines = ["## Data read", "", "| file | format | pair(s) | rows or messages | samples used | runs | "
             "not used or rebuilt |", "|---|---|---|---|---|---|---|"]
    totals = {"data_rows", "messages", "samples_used", "runs"}
    for item in inputs_read:
        counts = item.get("counts") or {}
        rows = counts.get("data_rows", counts.get("messages"))
        others = ", ".join(f"{name} {value}" for name, value in counts.items() if name not in totals and value)
        lines.append(f"| `{item['path']}` | {item['format']} | {'; '.join(item.get('openacc_pairs', [])) or '-'} | "
                     f"{fmt(rows)} | {fmt(counts.get('samples_used'))} | {fmt(counts.get('runs'))} | "
                     f"{others or ('none' if counts else 'not known')} |")
    return lines + [""]
