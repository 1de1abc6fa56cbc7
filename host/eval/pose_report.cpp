#include "host/eval/pose_report.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "host/eval/json_number.h"
#include "host/io/report_text.h"

namespace flexsight {

const char* const kPoseConventions =
    "BOP Challenge 2019+ (bop_toolkit eval_bop19_pose.py). Targets: ground-truth instances at least "
    "min_visib_fract visible. Per image and object only the best-scored estimates count, as many as "
    "there are targets; each, best score first, is matched to the unmatched target with the "
    "smallest error below the threshold. Recall = matched targets / targets over all images. "
    "ADD(-S) at 0.1 d: ADD-S (nearest vertex) for parts with a symmetry in models_info, ADD "
    "otherwise. AR_MSSD: mean recall at 0.05..0.5 d; AR_MSPD: at 5..50 px times width / 640; "
    "AR_VSD: at tau 0.05..0.5 d and thresholds 0.05..0.5, delta 15 mm (needs depth). AR = "
    "mean(AR_VSD, AR_MSSD, AR_MSPD). Model points: the CAD meshes' vertices.";

namespace {

using Json = nlohmann::ordered_json;

std::string ar_definition(const PoseScores& s) {
  return s.has_vsd ? "mean of ar_vsd, ar_mssd, ar_mspd"
                   : "mean of ar_mssd and ar_mspd: the data set has no depth, so no VSD";
}

// The score keys shared by the total and each object.
void put_scores(Json& json, const PoseScores& s) {
  json["add_recall"] = number_or_null(s.add_recall());
  json["add_recall_visib50"] = number_or_null(s.add_recall_visib50());
  json["ar"] = number_or_null(s.ar());
  json["ar_vsd"] = number_or_null(s.ar_vsd());
  json["ar_mssd"] = number_or_null(s.ar_mssd());
  json["ar_mspd"] = number_or_null(s.ar_mspd());
}

Json counts_json(const PoseScores& s) {
  Json counts;
  counts["ground_truth"] = s.ground_truth;
  counts["targets"] = s.targets;
  counts["targets_visib50"] = s.targets_visib50;
  counts["estimates"] = s.estimates;
  counts["estimates_evaluated"] = s.estimates_matched_against_targets;
  return counts;
}

Json curve(const RecallCounts& counts) {
  Json list = Json::array();
  const std::vector<double> recalls = counts.recalls();
  for (std::size_t k = 0; k < counts.thresholds.size(); ++k) {
    list.push_back({{"threshold", counts.thresholds[k]}, {"recall", number_or_null(recalls[k])}});
  }
  return list;
}

Json vsd_curves(const PoseScores& s, const PoseEvalSettings& settings) {
  if (!s.has_vsd) return nullptr;
  Json list = Json::array();
  const std::vector<double> recalls = s.vsd.recalls();
  const std::size_t per_tau = settings.vsd_thresholds.size();
  for (std::size_t t = 0; t < settings.vsd.taus.size(); ++t) {
    Json entry;
    entry["tau"] = settings.vsd.taus[t];
    Json row = Json::array();
    double sum = 0.0;
    for (std::size_t j = 0; j < per_tau; ++j) {
      row.push_back(number_or_null(recalls[t * per_tau + j]));
      sum += recalls[t * per_tau + j];
    }
    entry["recalls"] = row;
    entry["mean"] = number_or_null(sum / static_cast<double>(per_tau));
    list.push_back(entry);
  }
  return list;
}

}  // namespace

std::string to_json(const PoseReport& report) {
  const PoseScores& s = report.total;
  Json json;
  json["dataset"] = report.dataset;
  json["results"] = report.results;
  json["cad"] = report.cad;
  json["models_info"] = report.models_info;
  json["min_visib_fract"] = report.settings.min_visib_fract;
  put_scores(json, s);
  json["ar_definition"] = ar_definition(s);
  Json counts;
  counts["images"] = report.images;
  counts["images_skipped_mirrored"] = report.images_skipped_mirrored;
  counts["results_lines"] = report.results_lines;
  counts.update(counts_json(s));
  json["counts"] = counts;
  json["recalls"] = {{"add", curve(s.add)},
                     {"add_visib50", curve(s.add_visib50)},
                     {"mssd", curve(s.mssd)},
                     {"mspd", curve(s.mspd)},
                     {"vsd", vsd_curves(s, report.settings)}};
  Json objects = Json::object();
  for (const auto& [obj_id, scores] : report.per_object) {
    Json entry;
    put_scores(entry, scores);
    const auto symmetric = report.symmetric.find(obj_id);
    entry["add_metric"] = symmetric != report.symmetric.end() && symmetric->second ? "ADD-S" : "ADD";
    entry["counts"] = counts_json(scores);
    objects[std::to_string(obj_id)] = entry;
  }
  json["per_object"] = objects;
  json["conventions"] = kPoseConventions;
  return json.dump(2) + "\n";
}

std::string to_markdown(const PoseReport& report) {
  const PoseScores& s = report.total;
  std::string text = "# FlexSight pose evaluation\n\n";
  text += "- Data set: `" + report.dataset + "` (" + std::to_string(report.images) + " images";
  if (report.images_skipped_mirrored > 0) {
    text += "; " + std::to_string(report.images_skipped_mirrored) + " mirrored images left out";
  }
  text += ", " + std::to_string(s.ground_truth) + " ground-truth instances, " + std::to_string(s.targets) +
          " targets at visib_fract >= " + fraction_text(report.settings.min_visib_fract) + ")\n";
  text += "- Results: `" + report.results + "` (" + std::to_string(report.results_lines) + " estimates, " +
          std::to_string(s.estimates_matched_against_targets) + " evaluated)\n";
  text += "- Models: `" + report.cad + "`, symmetries from `" + report.models_info + "`\n";
  text += std::string("- Conventions: ") + kPoseConventions + "\n\n";

  text += "## Summary\n\n| metric | value |\n|---|---:|\n";
  text += "| ADD(-S) recall at 0.1 d | " + fraction_text(s.add_recall()) + " |\n";
  text += "| ADD(-S) recall, targets >= 50 % visible | " + fraction_text(s.add_recall_visib50()) + " |\n";
  text += "| AR (" + ar_definition(s) + ") | " + fraction_text(s.ar()) + " |\n";
  text += "| AR_VSD | " + (s.has_vsd ? fraction_text(s.ar_vsd()) : std::string("- (no depth)")) + " |\n";
  text += "| AR_MSSD | " + fraction_text(s.ar_mssd()) + " |\n";
  text += "| AR_MSPD | " + fraction_text(s.ar_mspd()) + " |\n";

  text += "\n## Per object\n\n| obj_id | ADD metric | targets | estimates | ADD(-S) recall | "
          "ADD(-S) >= 50 % visible | AR | AR_VSD | AR_MSSD | AR_MSPD |\n"
          "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& [obj_id, o] : report.per_object) {
    const auto symmetric = report.symmetric.find(obj_id);
    const bool adds = symmetric != report.symmetric.end() && symmetric->second;
    text += "| " + std::to_string(obj_id) + " | " + (adds ? "ADD-S" : "ADD") + " | " + std::to_string(o.targets) +
            " | " + std::to_string(o.estimates) + " | " + fraction_text(o.add_recall()) + " | " +
            fraction_text(o.add_recall_visib50()) + " | " + fraction_text(o.ar()) + " | " + fraction_text(o.ar_vsd()) + " | " +
            fraction_text(o.ar_mssd()) + " | " + fraction_text(o.ar_mspd()) + " |\n";
  }
  text += "\nAn object without targets shows `-`: it enters no recall.\n";
  return text;
}

}  // namespace flexsight
