// The HTML page of a comparison (rt/image/image_diff.h, rtdiff --html).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rt/image/image_diff.h"

namespace rt {
namespace {

std::string html(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// A relative path as a URL: every byte but unreserved ones and '/' percent-encoded.
std::string url(const std::string& path) {
    static const char* const hex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : path) {
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
            c == '.' || c == '~' || c == '/') {
            out += char(c);
        } else {
            out += '%';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// An image with its caption, or a note when there is none.
std::string figure(const std::string& link, const std::string& caption) {
    if (link.empty())
        return "<figure><div class=none>no image</div><figcaption>" + html(caption) + "</figcaption></figure>";
    return "<figure><a href=\"" + url(link) + "\"><img src=\"" + url(link) + "\" alt=\"" + html(caption) +
           "\"></a><figcaption>" + html(caption) + "</figcaption></figure>";
}

// The pair's worst pixels as a list, or nothing when no pixel differs.
std::string worst_list(const std::vector<PixelDiff>& worst) {
    if (worst.empty()) return "";
    std::string out = "<p>worst pixels (x,y as <code>raytracer --trace X,Y</code> takes them):</p>\n<ul class=worst>";
    for (const PixelDiff& p : worst) out += "<li>" + html(pixel_text(p)) + "</li>";
    return out + "</ul>\n";
}

}  // namespace

std::string diff_page_html(const std::string& a_label, const std::string& b_label, int tolerance,
                           const std::vector<DiffPageRow>& rows, const std::vector<std::string>& only_a,
                           const std::vector<std::string>& only_b) {
    bool verdicts = false;
    for (const DiffPageRow& r : rows) verdicts = verdicts || !r.verdict.empty();
    const std::string verdict_th = verdicts ? "<th>verdict</th>" : "";
    std::string p = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>rtdiff: " + html(a_label) + " vs " +
                    html(b_label) +
                    "</title>\n<style>\n"
                    "body{font-family:sans-serif;margin:1em 2em;background:#fafafa}\n"
                    "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}\n"
                    "td:first-child,th:first-child,td.l{text-align:left}tr.bad td{background:#fdd}\n"
                    ".row{display:flex;gap:12px;align-items:flex-start}figure{margin:0}\n"
                    "figure img{max-width:420px;image-rendering:pixelated;border:1px solid #999}\n"
                    ".none{width:200px;height:100px;border:1px dashed #999;display:flex;align-items:center;"
                    "justify-content:center;color:#999}\n"
                    "</style></head><body>\n<h1>rtdiff</h1>\n<p>A: <code>" +
                    html(a_label) + "</code><br>B: <code>" + html(b_label) + "</code><br>" +
                    std::to_string(rows.size()) +
                    (verdicts          ? " scenes, worst first"
                     : rows.size() > 1 ? " compared, worst first"
                                       : " compared") +
                    "; a pixel is off when some channel differs by more than " + std::to_string(tolerance) +
                    ". Heatmap: A dimmed where equal, dark blue within the tolerance, yellow to red above it; "
                    "its legend is the strip below it.</p>\n"
                    "<table id=summary><tr><th>image</th>" +
                    verdict_th +
                    "<th>size</th><th>max</th><th>mean</th><th>% off</th><th>PSNR</th>"
                    "<th>box</th></tr>\n";
    for (size_t i = 0; i < rows.size(); ++i) {
        const DiffPageRow& r = rows[i];
        const std::string name = "<a href=\"#img" + std::to_string(i) + "\">" + html(r.name) + "</a>" +
                                 (verdicts ? "</td><td class=l>" + html(r.verdict) : "");
        const bool bad = r.failed || (!r.error.empty() && !r.skipped);
        p += bad ? "<tr class=bad><td>" : "<tr><td>";
        if (!r.error.empty()) {
            p += name + "</td><td class=l colspan=6>" + html(r.error) + "</td></tr>\n";
            continue;
        }
        p += name + "</td><td>" + std::to_string(r.c.width) + "x" + std::to_string(r.c.height) + "</td><td>" +
             std::to_string(r.c.max_diff) + "</td><td>" + fmt("%.4f", r.c.mean_diff) + "</td><td>" +
             fmt("%.4f", r.c.pct_over) + "</td><td>" + psnr_text(r.c.psnr) + "</td><td>" + box_text(r.c) +
             "</td></tr>\n";
    }
    p += "</table>\n";
    if (!only_a.empty() || !only_b.empty()) {
        p += "<h2>Missing on one side</h2>\n<ul id=missing>\n";
        for (const std::string& n : only_a) p += "<li>only in A: " + html(n) + "</li>\n";
        for (const std::string& n : only_b) p += "<li>only in B: " + html(n) + "</li>\n";
        p += "</ul>\n";
    }
    for (size_t i = 0; i < rows.size(); ++i) {
        const DiffPageRow& r = rows[i];
        p += "<h2 id=img" + std::to_string(i) + ">" + html(r.name) + "</h2>\n<p>" +
             (r.error.empty() ? "max " + std::to_string(r.c.max_diff) + ", " + fmt("%.4f", r.c.pct_over) +
                                    "% off, PSNR " + psnr_text(r.c.psnr) + ", box " + box_text(r.c)
                              : html(r.error)) +
             "</p>\n" + worst_list(r.worst) + "<div class=row>" + figure(r.a_link, "A") + figure(r.b_link, "B") +
             figure(r.heatmap_link, "heatmap") + "</div>\n";
    }
    return p + "</body></html>\n";
}

}  // namespace rt
